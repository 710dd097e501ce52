#include <vimlop/Evaluation/WorldPreset.h>

#include <vimlop/Core/Error.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

const std::vector<ErrorSource>& errorSources()
{
  // Each clinical value is the realistic one of Documentation/Simulation.md,
  // where its source (or "estimate") is given.
  static const std::vector<ErrorSource> sources = {
    { "anatomy", "largest deformation of the patient from the template, mm", 0.0, 5.0,
      [](WorldSettings& w, double v) { w.model.anatomyDeformationMm = v; } },
    { "segmentation", "truth's air threshold minus the model's, HU (truth at full resolution)", 0.0,
      -100.0,
      [](WorldSettings& w, double v)
      {
        w.model.segmentationOffsetHU = v;
        w.model.truthTriangles = v == 0.0 ? w.model.surface.targetTriangles : 0;
      } },
    { "swelling", "largest mucosal swelling, mm", 0.0, 1.5,
      [](WorldSettings& w, double v) { w.model.swelling.swellingMm = v; } },
    { "image-circle", "radius of the image circle, fraction of the half-diagonal (vignetting 0.4)",
      0.0, 0.6,
      [](WorldSettings& w, double v)
      {
        w.video.fieldStop.radiusFraction = v;
        w.video.fieldStop.vignettingStrength = v == 0.0 ? 0.0 : 0.4;
      } },
    { "lens", "radial distortion k1 (k2 = -0.29 k1)", 0.0, -0.35,
      [](WorldSettings& w, double v)
      {
        if (v == 0.0)
        {
          w.video.intrinsics.distortion.resize(0);
        }
        else
        {
          w.video.intrinsics.distortion = Eigen::Vector4d(v, -v / 3.5, 0.0, 0.0);
        }
      } },
    { "calibration", "relative focal error (principal point off by 300 and -200 times it, px)", 0.0,
      0.01,
      [](WorldSettings& w, double v)
      {
        w.video.calibrationFocalErrorRelative = v;
        w.video.calibrationPrincipalPointErrorPx = Eigen::Vector2d(300.0 * v, -200.0 * v);
      } },
    { "tracker", "tracker latency, s (clock offset 5/3 of it)", 0.0, 0.03,
      [](WorldSettings& w, double v)
      {
        w.video.trackerLatencyS = v;
        w.video.trackerClockOffsetS = v * 5.0 / 3.0;
      } },
    { "roll", "largest roll of the scope from upright, deg", 10.0, 45.0,
      [](WorldSettings& w, double v) { w.video.trajectory.uprightRollDeg = v; } },
    { "motion-blur", "exposure time, s", 0.0, 1.0 / 60.0,
      [](WorldSettings& w, double v) { w.video.artifacts.exposureTimeS = v; } },
    { "specular", "strength of the specular highlights, fraction of full scale", 0.0, 1.0,
      [](WorldSettings& w, double v) { w.video.artifacts.specularStrength = v; } },
    { "exposure", "exposure gain (over-exposure above 1)", 1.0, 1.3,
      [](WorldSettings& w, double v) { w.video.artifacts.exposureGain = v; } },
    { "shot-noise", "shot noise, grey levels of variance per grey level", 0.0, 0.2,
      [](WorldSettings& w, double v) { w.video.artifacts.shotNoise = v; } },
    { "compression", "Motion JPEG quality lost, 100 - quality (0: no compression)", 0.0, 25.0,
      [](WorldSettings& w, double v)
      {
        VideoArtifactOptions& a = w.video.artifacts;
        a.compression = v == 0.0 ? VideoCompression::None : VideoCompression::Mjpg;
        a.compressionQuality =
          v == 0.0 ? 0 : std::clamp(static_cast<int>(std::lround(100.0 - v)), 1, 100);
      } },
    { "occluders", "fraction of frames with fluid on the lens (10 % of the frame each)", 0.0, 0.1,
      [](WorldSettings& w, double v) { w.video.artifacts.occludedFrameFraction = v; } },
    // The path's motion: outside the clinical preset (inClinicalPreset
    // false), since the README's clinical figures were measured without them.
    { "fast-motion", "advance along the passage per frame, mm", 0.5, 1.5,
      [](WorldSettings& w, double v) { w.video.trajectory.stepMm = v; }, false },
    { "jitter", "hand tremor, RMS offset of the optical centre per frame, mm (view: 2 deg per mm)",
      0.0, 0.25,
      [](WorldSettings& w, double v)
      {
        w.video.trajectory.jitterMm = v;
        w.video.trajectory.jitterDeg = 2.0 * v;
      },
      false },
    { "curved-path", "turn of the path's axis, deg per mm", 0.0, 1.0,
      [](WorldSettings& w, double v) { w.video.trajectory.turnDegPerMm = v; }, false },
  };
  return sources;
}

const ErrorSource& errorSource(const std::string& name)
{
  std::string known;
  for (const ErrorSource& s : errorSources())
  {
    if (s.name == name)
    {
      return s;
    }
    known += (known.empty() ? "" : ", ") + s.name;
  }
  throw Error("unknown error source '" + name + "' (expected one of " + known + ")");
}

void applyWorldPreset(WorldSettings& settings, const std::string& name)
{
  if (name != "ideal" && name != "clinical")
  {
    throw Error("unknown world '" + name + "' (expected ideal or clinical)");
  }
  for (const ErrorSource& s : errorSources())
  {
    if (s.inClinicalPreset)
    {
      s.set(settings, name == "ideal" ? s.offValue : s.clinicalValue);
    }
  }
}

} // namespace vimlop
