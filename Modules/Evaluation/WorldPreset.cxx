#include <vimlop/Evaluation/WorldPreset.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/LensDistortionRendering.h>

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
        PinholeCamera& k = w.video.intrinsics;
        if (v != 0.0)
        {
          k.lensModel = LensModel::RadialTangential;
          k.distortion = Eigen::Vector4d(v, -v / 3.5, 0.0, 0.0);
        }
        else if (k.lensModel == LensModel::RadialTangential)
        {
          // Off leaves a fisheye alone: it is the "fisheye" source's.
          k.removeDistortion();
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
    // Budget-only sources (inClinicalPreset false): the clinical figures of
    // the README were measured without them.
    { "fisheye",
      "fisheye strength: 0 the pinhole lens, 1 the equidistant one (fisheye k1..k4 = (1 - s) "
      "times tan's Taylor coefficients 1/3, 2/15, 17/315, 62/2835)",
      0.0, 1.0,
      [](WorldSettings& w, double v)
      {
        PinholeCamera& k = w.video.intrinsics;
        if (v != 0.0)
        {
          // theta (1 + theta^2 / 3 + 2 theta^4 / 15 + ...) is tan(theta)'s
          // series: at small s the fisheye is nearly the pinhole (0.3 px
          // apart at the corners of the 77° x 62° view), so that the budget's
          // sweep from off is continuous.
          k.lensModel = LensModel::Fisheye;
          k.distortion =
            (1.0 - v) * Eigen::Vector4d(1.0 / 3.0, 2.0 / 15.0, 17.0 / 315.0, 62.0 / 2835.0);
        }
        else if (k.lensModel == LensModel::Fisheye)
        {
          // Off leaves a radial-tangential lens alone: it is the "lens" source's.
          k.removeDistortion();
        }
      },
      false },
    { "distortion-calibration",
      "relative error of the given distortion coefficients (with the lens k1 = -0.35, k2 = 0.1 "
      "when there is none)",
      0.0, 0.03,
      [](WorldSettings& w, double v)
      {
        // Without a lens the error has nothing to act on: on, it switches on
        // the "lens" source's lens; off, it removes a radial-tangential lens
        // (the one it switched on; a fisheye stays).
        w.video.calibrationDistortionErrorRelative = v;
        PinholeCamera& k = w.video.intrinsics;
        if (v != 0.0 && !k.hasDistortion())
        {
          k.lensModel = LensModel::RadialTangential;
          k.distortion = Eigen::Vector4d(-0.35, 0.1, 0.0, 0.0);
        }
        else if (v == 0.0 && k.lensModel == LensModel::RadialTangential)
        {
          k.removeDistortion();
        }
      },
      false },
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
    if (name == "ideal")
    {
      s.set(settings, s.offValue);
    }
    else if (s.inClinicalPreset)
    {
      s.set(settings, s.clinicalValue);
    }
  }
}

} // namespace vimlop
