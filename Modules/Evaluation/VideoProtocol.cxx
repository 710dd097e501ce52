#include <vimlop/Evaluation/VideoProtocol.h>

#include <vimlop/Core/CanonicalStarts.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/SimulatedVideoCase.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <chrono>
#include <cmath>
#include <random>
#include <sstream>

namespace vimlop
{

namespace
{

nlohmann::json errorsJson(const VideoCameraErrors& e)
{
  return { { "camera_position_mm", { { "mean", e.positionMeanMm }, { "max", e.positionMaxMm } } },
    { "camera_angle_deg", { { "mean", e.angleMeanDeg }, { "max", e.angleMaxDeg } } },
    { "scale_error_rel", e.scaleErrorRel }, { "runtime_s", e.runtimeS } };
}

nlohmann::json methodJson(const VideoProtocolMethodReport& m)
{
  nlohmann::json j = errorsJson(m.errors);
  if (m.multiStart)
  {
    const VideoMultiStartFigures& f = *m.multiStart;
    j.update({ { "failure_flag", f.failureFlag }, { "contour_error_px", f.contourErrorPx },
      { "matched_fraction", f.matchedFraction }, { "failure_threshold_px", f.failureThresholdPx },
      { "failure_residual_mm", f.failureResidualMm }, { "winner", f.winner },
      { "skipped_candidates", f.skippedCandidates } });
  }
  return j;
}

} // namespace

std::vector<std::string> VideoProtocolReport::summaryLines() const
{
  const ContourScores& c = this->contours;
  std::vector<std::string> lines{ std::isnan(c.precision)
      ? formatText("P2 contours: not scored (lens distortion); SfM (%s) %d points",
          this->sfm.c_str(), static_cast<int>(this->sfmPoints))
      : formatText("P2 contours: precision %.3f, recall %.3f, median normal error %.1f deg; SfM "
                   "(%s) %d points",
          c.precision, c.recall, c.normalErrorDegMedian, this->sfm.c_str(),
          static_cast<int>(this->sfmPoints)) };
  for (const VideoProtocolMethodReport& m : this->methods)
  {
    const VideoCameraErrors& e = m.errors;
    lines.push_back(formatText("P2 %-6s camera %.3f mm (max %.3f) / %.3f deg (max %.3f), scale "
                               "error %.2f %%, runtime %.1f s",
      m.method.c_str(), e.positionMeanMm, e.positionMaxMm, e.angleMeanDeg, e.angleMaxDeg,
      100.0 * e.scaleErrorRel, e.runtimeS));
    if (m.multiStart)
    {
      lines.push_back(formatText("P2 %-6s multi-start of %d candidates: contour error %.2f px, %s",
        m.method.c_str(), static_cast<int>(this->candidates.value_or(0)),
        m.multiStart->contourErrorPx,
        m.multiStart->failureFlag ? "FLAGGED as a failure" : "not flagged"));
    }
  }
  return lines;
}

nlohmann::json VideoProtocolReport::toJson() const
{
  nlohmann::json result = { { "protocol", "P2" }, { "frames", this->frames },
    { "seed", this->seed }, { "sfm", this->sfm }, { "sfm_points", this->sfmPoints },
    { "contours",
      { { "precision", this->contours.precision }, { "recall", this->contours.recall },
        { "normal_error_deg_median", this->contours.normalErrorDegMedian } } },
    { "sfm_floor", errorsJson(this->sfmFloor) }, { "init", this->init } };
  if (this->candidates)
  {
    result["candidates"] = *this->candidates;
  }
  nlohmann::json methodsJson = nlohmann::json::object();
  for (const VideoProtocolMethodReport& m : this->methods)
  {
    methodsJson[m.method] = methodJson(m);
  }
  result["methods"] = methodsJson;
  return result;
}

void VideoProtocolOptions::validate() const
{
  if (this->init != "perturbed" && this->init != "canonical")
  {
    throw Error("--init: expected 'perturbed' or 'canonical', got '" + this->init + "'");
  }
  if (this->sfm != "builtin" && this->sfm != "colmap")
  {
    throw Error("--sfm: expected 'builtin' or 'colmap', got '" + this->sfm + "'");
  }
  this->pipeline.validate();
}

VideoProtocolReport runVideoProtocol(
  const TriangleMesh& mesh, const VideoProtocolOptions& o, const EvaluationProgress& progress)
{
  o.validate();
  return runVideoProtocol(makeSimulatedWorld(mesh, SimulatedWorldOptions()), o, progress);
}

VideoProtocolReport runVideoProtocol(
  const SimulatedWorld& world, const VideoProtocolOptions& o, const EvaluationProgress& progress)
{
  o.validate();
  auto say = [&](const std::string& text) { reportEvaluationNote(progress, "P2: " + text); };
  VideoProtocolOptions simulated = o;
  if (o.init == "canonical" && simulated.simulation.trajectory.uprightRollDeg < 0.0)
  {
    // Canonical poses assume the scope is held upright (see CanonicalPoses.h).
    simulated.simulation.trajectory.uprightRollDeg = o.uprightRollDeg;
  }
  const SimulatedVideoCase c = prepareSimulatedVideoCase(world, simulated, progress);
  const RegistrationModel& model = c.pipeline->model();

  VideoProtocolReport report;
  report.frames = o.simulation.frames;
  report.seed = o.simulation.seed;
  report.sfm = o.sfm;
  report.sfmPoints = c.sfm.points.size();
  report.contours = c.contourScores;
  report.sfmFloor = c.floor;
  report.init = o.init;

  const VideoRegistrationOptions& settings = o.pipeline;
  std::vector<SimilarityTransform> starts;
  if (o.init == "perturbed")
  {
    std::mt19937_64 rng(o.simulation.seed * 2654435761ull + 99ull);
    starts.push_back(perturbedStart(
      c, model, rng, o.perturbMinMm, o.perturbMaxMm, o.perturbMinDeg, o.perturbMaxDeg));
  }
  else
  {
    // The template's poses carried into the patient when the world has
    // them, as a user would; otherwise generated along the model's airway.
    const std::vector<CameraPose> poses = world.canonicalPosesCT.empty()
      ? makeCanonicalPoses(model, settings.canonical)
      : world.canonicalPosesCT;
    int anchor = 0;
    starts = canonicalStarts(c.data, c.initialScale, poses, &anchor);
    report.candidates = poses.size() * settings.multiStart.scaleFactors.size();
    say("canonical poses: " + std::to_string(poses.size()) + " (frame " + std::to_string(anchor) +
      " placed at each), " + std::to_string(*report.candidates) + " candidates");
  }

  for (const RegistrationMethod method : { RegistrationMethod::VIMLOP, RegistrationMethod::IMLP })
  {
    RegistrationOptions options = settings.registrationOptions(c.initialScale);
    options.method = method;
    const auto start = std::chrono::steady_clock::now();
    RegistrationResult r;
    VideoProtocolMethodReport m;
    m.method = toString(method);
    if (o.init == "perturbed")
    {
      r = registerVideo(model, c.data, starts.front(), options);
    }
    else
    {
      MultiStartOptions multi = settings.multiStart;
      multi.registration = options;
      multi.threads = settings.registration.threads;
      const MultiStartResult ms = registerMultiStart(model, c.data, starts, multi,
        [&](const char* phase, int done, int total)
        {
          // A note every 20 candidates: the multi-start's pace in a log.
          if (!progress || (done != total && done % 20 != 0))
          {
            return true;
          }
          std::ostringstream note;
          note << "P2: " << toString(method) << " multi-start " << phase << " " << done << "/"
               << total;
          return progress(note.str(), 0, 0);
        });
      r = ms.best;
      VideoMultiStartFigures f;
      for (const MultiStartCandidate& candidate : ms.candidates)
      {
        f.skippedCandidates += !candidate.skipped.empty();
      }
      f.failureFlag = ms.failure;
      f.contourErrorPx = ms.best.contourErrorPx;
      f.matchedFraction = matchedContourFraction(ms.best);
      f.failureThresholdPx = ms.failureThresholdPx;
      f.failureResidualMm = ms.failureResidualMm;
      f.winner = ms.bestCandidate;
      m.multiStart = f;
    }
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m.errors = cameraErrors(c, r.sfmToCT, seconds);
    say(m.method + ": " + methodJson(m).dump() + " (" + toString(r.termination) + " after " +
      std::to_string(r.iterations) + " iterations)");
    report.methods.push_back(m);
  }
  return report;
}

} // namespace vimlop
