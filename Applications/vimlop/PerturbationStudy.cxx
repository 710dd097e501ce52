#include "PerturbationStudy.h"

#include "EmbreeRegistrationModel.h"
#include "Error.h"
#include "MultiStartRegistration.h"
#include "Registration.h"
#include "Statistics.h"
#include "TaskPool.h"

#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <ostream>

namespace vimlop
{

void PerturbationStudyOptions::validate() const
{
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

nlohmann::json runPerturbationStudy(const TriangleMesh& mesh, const PerturbationStudyOptions& o,
  std::vector<PerturbationRun>& runs, std::ostream* progress)
{
  o.validate();
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  const VideoCase c = prepareVideoCase(model, o.video, progress);
  RegistrationOptions options =
    videoRegistrationOptions(c.initialScale, o.video, RegistrationMethod::VIMLOP);
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
  runs.assign(total, PerturbationRun());
  // The flag's score: the contour error, or infinity for a pose that matches
  // too few video contour points (its mean error over no matches says nothing).
  const MultiStartOptions flag;
  std::vector<double> scores(total);
  std::mutex progressMutex;
  int done = 0;
  TaskPool(o.video.threads)
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
          *progress << "P3: run " << ++done << "/" << total << ": offset " << run.offsetMm
                    << " mm/deg, camera error " << run.finalErrorMm << " mm, contour error "
                    << run.contourErrorPx << " px\n";
        }
      });

  nlohmann::json offsets = nlohmann::json::array();
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
    offsets.push_back({ { "offset_mm", o.offsets[k] }, { "offset_deg", o.offsets[k] },
      { "trials", perOffset }, { "success_rate", static_cast<double>(successes) / perOffset },
      { "camera_position_mm_median", summarize(position).median },
      { "contour_error_px_median", summarize(contour).median } });
  }
  // Failures are the positives: a high contour error should flag them.
  const double auc = rocAuc(failed, succeeded);
  const double threshold = bestSeparatingThreshold(failed, succeeded);
  auto numberOrNull = [](double x)
  { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
  return { { "protocol", "P3" }, { "seed", o.video.simulation.seed }, { "success_mm", o.successMm },
    { "sfm_points", c.sfm.points.size() }, { "offsets", offsets }, { "runs_total", total },
    { "failures", failed.size() }, { "auc", numberOrNull(auc) },
    { "failure_threshold_px", numberOrNull(threshold) } };
}

} // namespace vimlop
