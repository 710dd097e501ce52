#include <vimlop/Evaluation/PerturbationProtocol.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/Registration.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/TaskPool.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/SimulatedVideoCase.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <sstream>

namespace vimlop
{

void PerturbationProtocolOptions::validate() const
{
  this->video.validate();
  if (this->offsets.empty() || this->trialsPerOffset < 1)
  {
    throw Error("P3: need at least one offset and one trial per offset");
  }
  for (double offset : this->offsets)
  {
    if (!(offset >= 0.0) || offset > 90.0)
    {
      throw Error(
        "P3: offsets must lie in [0, 90] (mm and degrees), got " + std::to_string(offset));
    }
  }
  if (!(this->successMm > 0.0))
  {
    throw Error("P3: the success bound must be positive");
  }
}

std::vector<std::string> PerturbationProtocolReport::summaryLines() const
{
  std::vector<std::string> lines;
  for (const PerturbationOffsetReport& o : this->offsets)
  {
    lines.push_back(formatText("P3 offset %4.1f mm / %4.1f deg: success %3.0f %%, camera error "
                               "median %.3f mm, contour error median %.2f px",
      o.offsetMm, o.offsetDeg, 100.0 * o.successRate, o.cameraPositionMedianMm,
      o.contourErrorMedianPx));
  }
  if (!this->auc)
  {
    lines.push_back(formatText("P3 %s; no ROC area (it needs both successes and failures)",
      this->failures == 0 ? "every run succeeded" : "every run failed"));
  }
  else
  {
    lines.push_back(formatText("P3 contour error separates failures from successes: ROC AUC %.3f, "
                               "best threshold %.2f px (%d failures of %d runs)",
      *this->auc, this->failureThresholdPx.value_or(0.0), static_cast<int>(this->failures),
      this->runsTotal));
  }
  return lines;
}

nlohmann::json PerturbationProtocolReport::toJson() const
{
  nlohmann::json offsetsJson = nlohmann::json::array();
  for (const PerturbationOffsetReport& o : this->offsets)
  {
    offsetsJson.push_back({ { "offset_mm", o.offsetMm }, { "offset_deg", o.offsetDeg },
      { "trials", o.trials }, { "success_rate", o.successRate },
      { "camera_position_mm_median", o.cameraPositionMedianMm },
      { "contour_error_px_median", o.contourErrorMedianPx } });
  }
  auto numberOrNull = [](const std::optional<double>& x)
  { return x ? nlohmann::json(*x) : nlohmann::json(); };
  return { { "protocol", "P3" }, { "seed", this->seed }, { "success_mm", this->successMm },
    { "sfm_points", this->sfmPoints }, { "offsets", offsetsJson },
    { "runs_total", this->runsTotal }, { "failures", this->failures },
    { "auc", numberOrNull(this->auc) },
    { "failure_threshold_px", numberOrNull(this->failureThresholdPx) } };
}

PerturbationProtocolReport runPerturbationProtocol(const TriangleMesh& mesh,
  const PerturbationProtocolOptions& o, const EvaluationProgress& progress)
{
  o.validate();
  const SimulatedVideoCase c =
    prepareSimulatedVideoCase(makeSimulatedWorld(mesh, SimulatedWorldOptions()), o.video, progress);
  const RegistrationModel& model = c.pipeline->model();
  RegistrationOptions options = o.video.pipeline.registrationOptions(c.initialScale);
  options.method = RegistrationMethod::VIMLOP;
  options.threads = 1;

  // Every start is drawn first, from its own stream, so that the runs do not
  // depend on the order in which threads take them.
  const int perOffset = o.trialsPerOffset;
  const int total = static_cast<int>(o.offsets.size()) * perOffset;
  std::vector<SimilarityTransform> starts(total);
  for (int i = 0; i < total; ++i)
  {
    const double offset = o.offsets[i / perOffset];
    std::mt19937_64 rng(o.video.simulation.seed * 1000003ull + static_cast<std::uint64_t>(i));
    starts[i] = perturbedStart(c, model, rng, offset, offset, offset, offset);
  }
  PerturbationProtocolReport report;
  std::vector<PerturbationRun>& runs = report.runs;
  runs.assign(total, PerturbationRun());
  // The flag's score: the contour error, or infinity for a pose that matches
  // too few video contour points (its mean error over no matches says nothing).
  const MultiStartOptions flag;
  std::vector<double> scores(total);
  std::mutex progressMutex;
  int done = 0;
  TaskPool(o.video.pipeline.registration.threads)
    .run(total,
      [&](int i)
      {
        const RegistrationResult r = registerVideo(model, c.data, starts[i], options);
        const std::vector<double> errors = cameraPositionErrorsMm(c, r.sfmToCT);
        PerturbationRun& run = runs[i];
        run.offsetMm = run.offsetDeg = o.offsets[i / perOffset];
        run.finalErrorMm =
          std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
        run.contourErrorPx = r.contourErrorPx;
        run.success = run.finalErrorMm <= o.successMm;
        scores[i] = matchedContourFraction(r) >= flag.minMatchedFraction
          ? r.contourErrorPx
          : std::numeric_limits<double>::infinity();
        if (progress)
        {
          std::lock_guard<std::mutex> lock(progressMutex);
          std::ostringstream note;
          note << "P3: run " << ++done << "/" << total << ": offset " << run.offsetMm
               << " mm/deg, camera error " << run.finalErrorMm << " mm, contour error "
               << run.contourErrorPx << " px";
          reportEvaluationNote(progress, note.str()); // TaskPool rethrows a cancellation
        }
      });

  std::vector<double> failed;
  std::vector<double> succeeded;
  for (size_t k = 0; k < o.offsets.size(); ++k)
  {
    std::vector<double> position;
    std::vector<double> contour;
    int successes = 0;
    for (int t = 0; t < perOffset; ++t)
    {
      const PerturbationRun& run = runs[k * perOffset + t];
      position.push_back(run.finalErrorMm);
      contour.push_back(run.contourErrorPx);
      successes += run.success;
      (run.success ? succeeded : failed).push_back(scores[k * perOffset + t]);
    }
    PerturbationOffsetReport offset;
    offset.offsetMm = offset.offsetDeg = o.offsets[k];
    offset.trials = perOffset;
    offset.successRate = static_cast<double>(successes) / perOffset;
    offset.cameraPositionMedianMm = summarize(position).median;
    offset.contourErrorMedianPx = summarize(contour).median;
    report.offsets.push_back(offset);
  }
  // Failures are the positives: a high contour error should flag them.
  const double auc = rocAuc(failed, succeeded);
  const double threshold = bestSeparatingThreshold(failed, succeeded);
  report.seed = o.video.simulation.seed;
  report.successMm = o.successMm;
  report.sfmPoints = c.sfm.points.size();
  report.runsTotal = total;
  report.failures = failed.size();
  if (std::isfinite(auc))
  {
    report.auc = auc;
  }
  if (std::isfinite(threshold))
  {
    report.failureThresholdPx = threshold;
  }
  return report;
}

} // namespace vimlop
