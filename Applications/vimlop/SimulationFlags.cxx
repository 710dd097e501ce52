#include "CommandLine.h"
#include "TerminalEvaluationProgress.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Evaluation/WorldPreset.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/ModelLoading.h>
#include <vimlop/Rendering/OffscreenRendering.h>

#include <CLI/CLI.hpp>

namespace vimlop
{

namespace
{

/// Sets coefficient `index` of OpenCV's (k1, k2, p1, p2). The intrinsics carry
/// coefficients only once one is set, so that the ideal world's
/// intrinsics.yaml stays as it was. A fisheye of the world preset gives way
/// to the radial-tangential lens (the flag --fisheye itself excludes these).
void setDistortion(PinholeCamera& k, int index, double value)
{
  if (k.distortion.size() < 4 || k.lensModel != LensModel::RadialTangential)
  {
    k.lensModel = LensModel::RadialTangential;
    k.distortion = Eigen::Vector4d::Zero();
  }
  k.distortion(index) = value;
}

Eigen::Vector2d pair(const std::vector<double>& v)
{
  return Eigen::Vector2d(v[0], v[1]);
}

} // namespace

void addSimulationOptions(CLI::App& c, EndoscopeSimulationOptions& s)
{
  FieldStopOptions& stop = s.fieldStop;
  c.add_option("--image-circle", stop.radiusFraction,
     "radius of the endoscope's image circle, fraction of the half-diagonal (0: none; about 0.6 "
     "for a circle as tall as a 4:3 frame)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option("--image-circle-px", stop.radiusPx,
     "radius of the image circle, pixels (0: none; instead of --image-circle)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option_function<std::vector<double>>(
     "--image-circle-offset-px",
     [&stop](const std::vector<double>& v) { stop.centreOffsetPx = pair(v); },
     "centre of the image circle relative to the image centre, pixels: u,v")
    ->delimiter(',')
    ->expected(2)
    ->default_str("0,0");
  c.add_option("--image-circle-edge-px", stop.edgeSoftnessPx,
     "width of the image circle's soft edge, pixels (0: a hard step)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option("--vignetting", stop.vignettingStrength,
     "fraction of brightness lost at the circle's edge (gain 1 - s (r/R)^2; 0: none)")
    ->capture_default_str();
  PinholeCamera& k = s.intrinsics;
  const char* names[] = { "--k1", "--k2", "--p1", "--p2" };
  const char* helps[] = { "radial distortion k1 rendered into the frames (OpenCV's model)",
    "radial distortion k2 (OpenCV)", "tangential distortion p1 (OpenCV)",
    "tangential distortion p2 (OpenCV)" };
  std::vector<CLI::Option*> radialTangential;
  for (int i = 0; i < 4; ++i)
  {
    radialTangential.push_back(c.add_option_function<double>(
                                  names[i], [&k, i](double v) { setDistortion(k, i, v); }, helps[i])
                                 ->default_str("0"));
  }
  CLI::Option* fisheye =
    c.add_option_function<std::vector<double>>(
       "--fisheye",
       [&k](const std::vector<double>& v)
       {
         k.lensModel = LensModel::Fisheye;
         k.distortion = Eigen::Vector4d(v[0], v[1], v[2], v[3]);
       },
       "a fisheye lens rendered into the frames instead (OpenCV's cv::fisheye, "
       "equidistant): k1,k2,k3,k4 (0,0,0,0 is the equidistant lens itself)")
      ->delimiter(',')
      ->expected(4);
  // One lens: the two models' coefficients do not mix.
  for (CLI::Option* option : radialTangential)
  {
    fisheye->excludes(option);
  }
  c.add_option("--distortion-error", s.calibrationDistortionErrorRelative,
     "relative error of the distortion coefficients written to intrinsics.yaml, every one alike "
     "(the frames use the true ones; in (-1, 1))")
    ->capture_default_str();
  c.add_option("--focal-error", s.calibrationFocalErrorRelative,
     "relative error of the focal length written to intrinsics.yaml (the frames use the true one)")
    ->capture_default_str();
  c.add_option_function<std::vector<double>>(
     "--principal-point-error-px",
     [&s](const std::vector<double>& v) { s.calibrationPrincipalPointErrorPx = pair(v); },
     "error of the principal point written to intrinsics.yaml, pixels: u,v")
    ->delimiter(',')
    ->expected(2)
    ->default_str("0,0");
  // The path's motion: no range checks here either, for the same one message.
  EndoscopeTrajectoryOptions& path = s.trajectory;
  c.add_option("--step-mm", path.stepMm,
     "advance along the passage per frame, mm (faster motion: larger steps)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c.add_option("--jitter-mm", path.jitterMm,
     "hand tremor: each optical centre moved off the smooth path by an independent random offset "
     "of this root-mean-square length, mm (0: none; about 0.1 to 0.5)")
    ->capture_default_str();
  c.add_option("--jitter-deg", path.jitterDeg,
     "hand tremor of the view: each view turned by an independent random rotation of this "
     "root-mean-square angle, degrees (0: none; about 0.5)")
    ->capture_default_str();
  c.add_option("--turn-deg-per-mm", path.turnDegPerMm,
     "curved path: the passage axis turns at this rate, degrees per mm of path (0: straight)")
    ->capture_default_str();
  c.add_option("--tracker-latency-s", s.trackerLatencyS,
     "tracker latency, seconds: each sample reports the tip this long before its time stamp")
    ->capture_default_str();
  c.add_option(
     "--tracker-offset-s", s.trackerClockOffsetS, "tracker clock minus video clock, seconds")
    ->capture_default_str();
  c.add_flag("--tracker-rotation", s.trackerRotation,
    "the tracker is a 6-DOF sensor: it records the camera's rotation too (tracker.csv's qw, qx, "
    "qy, qz columns)");
  c.add_option("--tracker-rotation-noise-deg", s.trackerRotationNoiseDeg,
     "the 6-DOF tracker's rotation noise, degrees per axis")
    ->capture_default_str();
  c.add_option("--tracker-position-bias-mm", s.trackerPositionBiasMm,
     "the tracker's registration to the CT off by this shift, mm (every tip alike)")
    ->capture_default_str();
  c.add_option("--tracker-rotation-bias-deg", s.trackerRotationBiasDeg,
     "the 6-DOF tracker's rotation off by this turn, degrees (registration and calibration to "
     "the camera; every sample alike)")
    ->capture_default_str();
  // The video artifacts: no range checks here, so that validate() names the
  // bad value in one message for the library and the command line alike.
  VideoArtifactOptions& a = s.artifacts;
  c.add_option("--exposure-time-s", a.exposureTimeS,
     "exposure time of each frame, seconds: motion blur from the camera's motion (0: none; about "
     "1/60 to 1/30 at 30 fps)")
    ->capture_default_str();
  c.add_option("--motion-blur-samples", a.motionBlurSamples,
     "instants of the exposure the motion blur averages")
    ->capture_default_str();
  c.add_option("--specular", a.specularStrength,
     "strength of the specular highlights, fraction of full scale at their centre (0: none; 1 to "
     "2 saturates)")
    ->capture_default_str();
  c.add_option("--specular-angle-deg", a.specularAngleDeg,
     "angle between the surface normal and the view ray within which a highlight is seen, degrees")
    ->capture_default_str();
  c.add_option("--exposure-gain", a.exposureGain,
     "exposure gain on the light, clipped to [0, 255] before the sensor noise (1: as rendered)")
    ->capture_default_str();
  c.add_option("--shot-noise", a.shotNoise,
     "shot noise: variance per grey level of the pixel's value (0: none; about 0.05 to 0.5)")
    ->capture_default_str();
  c.add_option_function<std::string>(
     "--compression",
     [&a](const std::string& name)
     {
       a.compression = name == "mjpg" ? VideoCompression::Mjpg
         : name == "h264"             ? VideoCompression::H264
         : name == "mp4v"             ? VideoCompression::Mp4v
                                      : VideoCompression::None;
     },
     "pass the frames through a lossy codec: none, mjpg (.avi), h264 or mp4v (.mp4)")
    ->check(CLI::IsMember({ "none", "mjpg", "h264", "mp4v" }))
    ->default_str("none");
  c.add_option("--compression-quality", a.compressionQuality,
     "JPEG quality of --compression mjpg, 1 to 100 (0: the writer's own, 75)")
    ->capture_default_str();
  c.add_option("--occluded-frames", a.occludedFrameFraction,
     "fraction of frames with occluders (fluid, blood on the lens; 0: none)")
    ->capture_default_str();
  c.add_option(
     "--occluder-area", a.occluderAreaFraction, "fraction of an occluded frame the occluders cover")
    ->capture_default_str();
  c.add_option("--occluder-opacity", a.occluderOpacity, "opacity of an occluder at its centre")
    ->capture_default_str();
  c.add_option("--wall-contact-frames", a.wallContactFraction,
     "fraction of frames in stretches where the lens touches the mucosa and sees a red blur "
     "(0: none)")
    ->capture_default_str();
  c.add_option("--wall-contact-length", a.wallContactFrames, "frames of each such stretch")
    ->capture_default_str();
}

void addWorldOptions(CLI::App& c, SimulatedWorldOptions& w)
{
  c.add_option("--anatomy-deformation-mm", w.anatomyDeformationMm,
     "model error from the template warp: the patient is the CT deformed by a smooth field of "
     "this largest displacement, the model the CT's airway warped to it (0: the CT is the patient)")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 20.0));
  c.add_option("--anatomy-seed", w.anatomySeed, "seed of the anatomy's deformation")
    ->capture_default_str();
  c.add_option("--segmentation-offset-hu", w.segmentationOffsetHU,
     "segmentation error: the truth is segmented at the model's air threshold plus this, HU")
    ->capture_default_str()
    ->check(CLI::Range(-300.0, 300.0));
  c.add_option("--truth-triangles", w.truthTriangles,
     "triangles of the truth surface (0: the full iso-surface; the model keeps its 30000)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c.add_option("--swelling-mm", w.swelling.swellingMm,
     "erectile tissue: the nasal cavity's turbinate and septal mucosa swollen into the air by up "
     "to this, mm")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 5.0));
}

void addWorldPresetOption(CLI::App& c, WorldSettings& settings)
{
  // Applied as soon as it is parsed, so that the knobs given with it, in any
  // order, change the preset rather than the other way round.
  c.add_option_function<std::string>(
     "--world", [&settings](const std::string& name) { applyWorldPreset(settings, name); },
     "every error source at once: ideal (all off, the scope upright within 10 deg) or clinical "
     "(all at their realistic values, Documentation/Simulation.md); the flags of single sources "
     "change it")
    ->trigger_on_parse();
}

SimulatedWorld loadSimulatedWorld(const std::string& mesh, const std::string& ct,
  const SimulatedWorldOptions& model, const std::string& command)
{
  model.validate();
  if (mesh.empty() == ct.empty())
  {
    throw Error("give exactly one of --mesh and --ct");
  }
  if (ct.empty())
  {
    model.requireMeshWorld();
  }
  requireOffscreenRendering(command);
  return ct.empty() ? makeSimulatedWorld(loadAirwayMesh(mesh), model)
                    : makeSimulatedWorld(readCTVolume(ct), model, terminalEvaluationProgress());
}

} // namespace vimlop
