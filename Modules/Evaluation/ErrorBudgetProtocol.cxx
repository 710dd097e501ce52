#include <vimlop/Evaluation/ErrorBudgetProtocol.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/MultiStartRegistration.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/SimulatedVideoCase.h>
#include <vimlop/Evaluation/SimulatedWorld.h>
#include <vimlop/Imaging/CTVolume.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <random>

namespace vimlop
{

namespace
{

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A condition to run: its account and its world's settings.
struct ConditionPlan
{
  BudgetCondition account;
  WorldSettings settings;
};

std::vector<ConditionPlan> planConditions(const ErrorBudgetOptions& o)
{
  WorldSettings ideal;
  ideal.video.frames = o.frames;
  applyWorldPreset(ideal, "ideal");
  std::vector<ConditionPlan> plans;
  if (o.ideal)
  {
    plans.push_back({ BudgetCondition{}, ideal });
    plans.back().account.name = "ideal";
  }
  std::vector<std::string> names = o.sources;
  if (names.empty())
  {
    for (const ErrorSource& s : errorSources())
    {
      names.push_back(s.name);
    }
  }
  for (const std::string& name : names)
  {
    const ErrorSource& source = errorSource(name);
    for (double level : o.levels)
    {
      ConditionPlan plan{ BudgetCondition{}, ideal };
      const double value = source.offValue + level * (source.clinicalValue - source.offValue);
      source.set(plan.settings, value);
      plan.account.name = level == 1.0 ? name : name + formatText("@%g", level);
      plan.account.source = name;
      plan.account.knob = source.knob;
      plan.account.value = value;
      plans.push_back(plan);
    }
  }
  if (o.clinical)
  {
    WorldSettings clinical = ideal;
    applyWorldPreset(clinical, "clinical");
    plans.push_back({ BudgetCondition{}, clinical });
    plans.back().account.name = "clinical";
  }
  return plans;
}

/// Targets for the TRE, CT frame: every 500th vertex of the truth (points on
/// the airway wall) and, near the sinus roof, points 3 mm above the five
/// highest vertices of the airway's front half (the skull base, which
/// navigation must not breach).
std::vector<Eigen::Vector3d> targetPoints(const TriangleMesh& truth)
{
  std::vector<Eigen::Vector3d> targets;
  const std::vector<Eigen::Vector3d>& v = truth.vertices();
  for (std::size_t i = 0; i < v.size(); i += 500)
  {
    targets.push_back(v[i]);
  }
  const Eigen::Matrix<double, 3, 2> bounds = truth.bounds();
  std::vector<Eigen::Vector3d> front;
  for (const Eigen::Vector3d& p : v)
  {
    if (p.y() < bounds.row(1).mean())
    {
      front.push_back(p);
    }
  }
  const std::size_t roof = std::min<std::size_t>(5, front.size());
  std::partial_sort(front.begin(), front.begin() + roof, front.end(),
    [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.z() > b.z(); });
  for (std::size_t i = 0; i < roof; ++i)
  {
    targets.push_back(front[i] + Eigen::Vector3d(0.0, 0.0, 3.0));
  }
  return targets;
}

/// One registration's outcome, with its errors at the targets.
struct Run
{
  BudgetRegistration record;
  std::vector<double> treMm;
};

/// The measures a confidence could use, from the result alone.
void describeConfidence(const RegistrationResult& result, BudgetRegistration& record)
{
  long long matched = 0;
  long long inliers = 0;
  std::vector<double> frameErrors;
  for (const FrameResult& f : result.frames)
  {
    matched += f.matched;
    inliers += f.inliers;
    if (f.matched > 0)
    {
      frameErrors.push_back(f.contourErrorPx);
    }
  }
  record.contourInlierFraction = matched > 0 ? static_cast<double>(inliers) / matched : 0.0;
  const auto pointInliers = std::count(result.pointInliers.begin(), result.pointInliers.end(), 1);
  record.pointInlierFraction = result.pointInliers.empty()
    ? 0.0
    : static_cast<double>(pointInliers) / static_cast<double>(result.pointInliers.size());
  record.residualErrorMm = result.residualErrorMm;
  if (!frameErrors.empty())
  {
    record.frameContourErrorMedianPx = summarize(frameErrors).median;
    record.frameContourErrorMaxPx = *std::max_element(frameErrors.begin(), frameErrors.end());
  }
}

/// The least final contour error of a finalist whose cameras ended more
/// than `apartMm` (mean) from the winner's, among those that matched enough
/// contour points to compete; empty when there is none.
std::optional<double> rivalContourError(const MultiStartResult& outcome,
  const RegistrationData& data, double apartMm, double minMatchedFraction)
{
  std::optional<double> rival;
  const SimilarityTransform& winner = outcome.best.sfmToCT;
  for (const MultiStartCandidate& c : outcome.candidates)
  {
    if (!c.finalist || c.matchedFraction < minMatchedFraction || data.frames.empty())
    {
      continue;
    }
    double apart = 0.0;
    for (const VideoFrame& f : data.frames)
    {
      apart +=
        (c.finalSfmToCT.apply(f.cameraToSfm.centre) - winner.apply(f.cameraToSfm.centre)).norm();
    }
    if (apart / static_cast<double>(data.frames.size()) > apartMm &&
      (!rival || c.contourErrorPx < *rival))
    {
      rival = c.contourErrorPx;
    }
  }
  return rival;
}

/// The figures of a method over its runs.
BudgetMethodFigures figuresOf(const std::vector<Run>& runs, double successMm)
{
  BudgetMethodFigures f;
  f.registrations = static_cast<int>(runs.size());
  if (runs.empty())
  {
    return f;
  }
  std::vector<double> position, angle, tre;
  std::vector<BudgetRegistration> records;
  double seconds = 0.0;
  int flagged = 0;
  for (const Run& run : runs)
  {
    const BudgetRegistration& r = run.record;
    position.push_back(r.cameraPositionMm);
    angle.push_back(r.cameraAngleDeg);
    tre.insert(tre.end(), run.treMm.begin(), run.treMm.end());
    flagged += r.flagged ? 1 : 0;
    seconds += r.seconds;
    records.push_back(r);
  }
  // Success and the contour error's AUC by the same rule as the pooled flag.
  const FailureFlagFigures flag = assessFailureFlag(records, successMm, successMm);
  f.cameraPositionMm = summarize(position);
  f.cameraAngleDeg = summarize(angle);
  f.treMm = summarize(tre);
  f.successRate = static_cast<double>(flag.registrations - flag.failures) / runs.size();
  f.flaggedRate = static_cast<double>(flagged) / runs.size();
  f.failureAuc = flag.contourErrorAuc;
  f.meanRuntimeS = seconds / runs.size();
  return f;
}

nlohmann::json summaryJson(const Summary& s)
{
  return { { "mean", s.mean }, { "median", s.median }, { "p95", s.p95 } };
}

nlohmann::json methodsJson(const std::map<std::string, BudgetMethodFigures>& methods)
{
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, f] : methods)
  {
    j[name] = { { "camera_position_mm", summaryJson(f.cameraPositionMm) },
      { "camera_angle_deg", summaryJson(f.cameraAngleDeg) },
      { "tre_mm", { { "median", f.treMm.median }, { "p95", f.treMm.p95 } } },
      { "success_rate", f.successRate },
      { "failure_auc", f.failureAuc ? nlohmann::json(*f.failureAuc) : nlohmann::json(nullptr) },
      { "flagged_rate", f.flaggedRate }, { "mean_runtime_s", f.meanRuntimeS },
      { "registrations", f.registrations } };
  }
  return j;
}

} // namespace

FailureFlagFigures assessFailureFlag(
  const std::vector<BudgetRegistration>& registrations, double successMm, double goodMm)
{
  FailureFlagFigures f;
  std::vector<double> failed, succeeded;
  for (const BudgetRegistration& r : registrations)
  {
    ++f.registrations;
    const bool failure = !(r.cameraPositionMm <= successMm);
    (failure ? failed : succeeded).push_back(r.contourErrorPx);
    f.failures += failure ? 1 : 0;
    f.missed += failure && !r.flagged ? 1 : 0;
    const bool good = r.cameraPositionMm < goodMm;
    f.good += good ? 1 : 0;
    f.falseFlags += good && r.flagged ? 1 : 0;
  }
  if (!failed.empty() && !succeeded.empty())
  {
    f.contourErrorAuc = rocAuc(failed, succeeded);
  }
  return f;
}

std::map<std::string, FailureFlagFigures> ErrorBudgetReport::failureFlag() const
{
  std::map<std::string, std::vector<BudgetRegistration>> byMethod;
  for (const BudgetRegistration& r : this->registrations)
  {
    byMethod[r.method].push_back(r);
  }
  std::map<std::string, FailureFlagFigures> figures;
  for (const auto& [method, registrations] : byMethod)
  {
    figures[method] = assessFailureFlag(registrations, this->successMm, this->goodMm);
  }
  return figures;
}

void ErrorBudgetOptions::validate() const
{
  if (this->seeds < 1)
  {
    throw Error("P5: --seeds must be at least 1");
  }
  if (this->frames < 3)
  {
    throw Error("P5: --frames must be at least 3");
  }
  for (const std::string& name : this->sources)
  {
    errorSource(name);
  }
  for (double level : this->levels)
  {
    if (!(level > 0.0 && level <= 4.0))
    {
      throw Error("P5: each level must lie in (0, 4], not " + formatText("%g", level));
    }
  }
  if (this->methods.empty())
  {
    throw Error("P5: no method to compare");
  }
  if (!this->canonicalStarts && !this->perturbedStarts)
  {
    throw Error("P5: neither canonical nor perturbed starts");
  }
  if (!(this->successMm > 0.0))
  {
    throw Error("P5: the success threshold must be positive");
  }
  if (!(this->goodMm > 0.0 && this->goodMm <= this->successMm))
  {
    throw Error("P5: the good threshold must be positive and at most the success threshold");
  }
  if (this->workFolder.empty())
  {
    throw Error("P5: a work folder is required");
  }
  this->pipeline.validate();
}

ErrorBudgetReport runErrorBudgetProtocol(
  const CTVolume& ct, const ErrorBudgetOptions& o, const EvaluationProgress& progress)
{
  o.validate();
  const auto start = std::chrono::steady_clock::now();
  auto say = [&](const std::string& text) { reportEvaluationNote(progress, "P5: " + text); };
  std::vector<ConditionPlan> plans = planConditions(o);
  ErrorBudgetReport report;
  report.seeds = o.seeds;
  report.frames = o.frames;
  report.successMm = o.successMm;
  report.goodMm = o.goodMm;
  const int total = static_cast<int>(plans.size()) * o.seeds;
  int done = 0;

  // Worlds whose model is the truth are all the ideal one: made once.
  std::unique_ptr<SimulatedWorld> idealWorld;
  for (ConditionPlan& plan : plans)
  {
    BudgetCondition& condition = plan.account;
    const auto conditionStart = std::chrono::steady_clock::now();
    say("condition " + condition.name);
    std::unique_ptr<SimulatedWorld> own;
    if (plan.settings.model.isIdealWorld() && !idealWorld)
    {
      idealWorld =
        std::make_unique<SimulatedWorld>(makeSimulatedWorld(ct, plan.settings.model, progress));
    }
    if (!plan.settings.model.isIdealWorld())
    {
      own = std::make_unique<SimulatedWorld>(makeSimulatedWorld(ct, plan.settings.model, progress));
    }
    const SimulatedWorld& world = own ? *own : *idealWorld;
    condition.truthToModelMeanMm = world.truthToModel.meanMm;
    const std::vector<Eigen::Vector3d> targets = targetPoints(world.truth);

    std::map<std::string, std::vector<Run>> canonicalRuns, perturbedRuns;
    std::vector<double> floorPosition, floorAngle;
    for (int k = 0; k < o.seeds; ++k)
    {
      const std::uint64_t seed = o.firstSeed + static_cast<std::uint64_t>(k);
      try
      {
        // The sequence, written as a user has it, and the main job on those
        // files through its data (the truth never reaches it).
        VideoProtocolOptions sequence;
        sequence.simulation = plan.settings.video;
        sequence.simulation.seed = seed;
        sequence.pipeline = o.pipeline;
        sequence.workFolder = o.workFolder;
        const SimulatedVideoCase c = prepareSimulatedVideoCase(world, sequence, progress);
        VideoRegistrationPipeline& pipeline = *c.pipeline;
        floorPosition.push_back(c.floor.positionMeanMm);
        floorAngle.push_back(c.floor.angleMeanDeg);
        const SimilarityTransform sfmFromCT = c.truth.inverse();

        auto registerEach = [&](
                              std::map<std::string, std::vector<Run>>& runs, const char* startKind)
        {
          for (RegistrationMethod method : o.methods)
          {
            RegistrationOptions r = o.pipeline.registration;
            r.method = method;
            pipeline.setRegistrationOptions(r);
            const auto t0 = std::chrono::steady_clock::now();
            pipeline.run();
            Run run;
            BudgetRegistration& record = run.record;
            record.condition = condition.name;
            record.seed = seed;
            record.start = startKind;
            record.method = toString(method);
            record.seconds = secondsSince(t0);
            const SimilarityTransform& estimate = pipeline.result().sfmToCT;
            const VideoCameraErrors e = cameraErrors(c, estimate, record.seconds);
            record.cameraPositionMm = e.positionMeanMm;
            record.cameraAngleDeg = e.angleMeanDeg;
            for (const Eigen::Vector3d& t : targets)
            {
              run.treMm.push_back((estimate.apply(sfmFromCT.apply(t)) - t).norm());
            }
            record.contourErrorPx = pipeline.result().contourErrorPx;
            record.matchedFraction = matchedContourFraction(pipeline.result());
            describeConfidence(pipeline.result(), record);
            record.rivalContourErrorPx = rivalContourError(pipeline.outcome(), pipeline.data(),
              o.successMm, o.pipeline.multiStart.minMatchedFraction);
            record.flagged = pipeline.flaggedAsFailure();
            report.registrations.push_back(record);
            runs[record.method].push_back(run);
          }
        };
        if (o.canonicalStarts)
        {
          pipeline.makeCanonicalStarts(
            world.canonicalPosesCT.empty() ? nullptr : &world.canonicalPosesCT,
            "the template's canonical poses");
          registerEach(canonicalRuns, "canonical");
        }
        if (o.perturbedStarts)
        {
          std::mt19937_64 rng(seed * 2654435761ull + 7ull);
          pipeline.setStarts({ perturbedStart(c, pipeline.model(), rng, o.perturbMinMm,
                               o.perturbMaxMm, o.perturbMinDeg, o.perturbMaxDeg) },
            StartMode::Manual);
          registerEach(perturbedRuns, "perturbed");
        }
      }
      catch (const PipelineCancelled&)
      {
        throw Error("P5: cancelled");
      }
      catch (const Error& e)
      {
        if (std::string(e.what()).find("cancelled") != std::string::npos)
        {
          throw;
        }
        condition.failedSequences.push_back(
          formatText("seed %llu: ", static_cast<unsigned long long>(seed)) + e.what());
        say(condition.name + ": " + condition.failedSequences.back());
      }
      reportEvaluationCount(progress, "P5: sequence", ++done, total);
    }
    for (const auto& [name, runs] : canonicalRuns)
    {
      condition.canonical[name] = figuresOf(runs, o.successMm);
    }
    for (const auto& [name, runs] : perturbedRuns)
    {
      condition.perturbed[name] = figuresOf(runs, o.successMm);
    }
    condition.floorPositionMm = summarize(floorPosition);
    condition.floorAngleDeg = summarize(floorAngle);
    condition.runtimeS = secondsSince(conditionStart);
    report.conditions.push_back(condition);
    ErrorBudgetReport one;
    one.conditions = { condition };
    for (const std::string& line : one.summaryLines())
    {
      reportEvaluationNote(progress, line);
    }
  }
  report.runtimeS = secondsSince(start);
  return report;
}

nlohmann::json ErrorBudgetReport::toJson() const
{
  nlohmann::json conditions = nlohmann::json::object();
  for (const BudgetCondition& c : this->conditions)
  {
    nlohmann::json j;
    j["methods"] = methodsJson(c.canonical);
    j["perturbed_start"] = { { "methods", methodsJson(c.perturbed) } };
    j["sfm_floor"] = { { "camera_position_mm", summaryJson(c.floorPositionMm) },
      { "camera_angle_deg", summaryJson(c.floorAngleDeg) } };
    if (!c.source.empty())
    {
      j["source"] = c.source;
      j["knob"] = c.knob;
      j["value"] = c.value;
    }
    j["truth_to_model_mean_mm"] = c.truthToModelMeanMm;
    j["failed_sequences"] = c.failedSequences;
    j["runtime_s"] = c.runtimeS;
    conditions[c.name] = j;
  }
  nlohmann::json registrations = nlohmann::json::array();
  for (const BudgetRegistration& r : this->registrations)
  {
    registrations.push_back({ { "condition", r.condition }, { "seed", r.seed },
      { "start", r.start }, { "method", r.method }, { "camera_position_mm", r.cameraPositionMm },
      { "camera_angle_deg", r.cameraAngleDeg }, { "contour_error_px", r.contourErrorPx },
      { "matched_fraction", r.matchedFraction },
      { "contour_inlier_fraction", r.contourInlierFraction },
      { "point_inlier_fraction", r.pointInlierFraction },
      { "residual_error_mm", r.residualErrorMm },
      { "frame_contour_error_median_px", r.frameContourErrorMedianPx },
      { "frame_contour_error_max_px", r.frameContourErrorMaxPx },
      { "rival_contour_error_px",
        r.rivalContourErrorPx ? nlohmann::json(*r.rivalContourErrorPx) : nlohmann::json(nullptr) },
      { "flagged", r.flagged }, { "runtime_s", r.seconds } });
  }
  nlohmann::json flag = nlohmann::json::object();
  for (const auto& [method, f] : this->failureFlag())
  {
    flag[method] = { { "registrations", f.registrations }, { "failures", f.failures },
      { "missed", f.missed }, { "good", f.good }, { "false_flags", f.falseFlags },
      { "contour_error_auc",
        f.contourErrorAuc ? nlohmann::json(*f.contourErrorAuc) : nlohmann::json(nullptr) } };
  }
  return { { "protocol", "P5" }, { "seeds", this->seeds }, { "frames", this->frames },
    { "conditions", conditions }, { "registrations", registrations },
    { "failure_flag",
      { { "success_mm", this->successMm }, { "good_mm", this->goodMm }, { "methods", flag } } },
    { "runtime_s", this->runtimeS } };
}

std::vector<std::string> ErrorBudgetReport::summaryLines() const
{
  std::vector<std::string> lines;
  for (const BudgetCondition& c : this->conditions)
  {
    for (const auto& [name, f] : c.canonical)
    {
      lines.push_back(formatText("P5 %-14s %-11s camera %.3f mm (p95 %.3f) / %.3f deg, TRE "
                                 "median %.3f mm, success %.0f %%, flagged %.0f %%",
        c.name.c_str(), name.c_str(), f.cameraPositionMm.median, f.cameraPositionMm.p95,
        f.cameraAngleDeg.median, f.treMm.median, 100.0 * f.successRate, 100.0 * f.flaggedRate));
    }
    for (const auto& [name, f] : c.perturbed)
    {
      lines.push_back(formatText("P5 %-14s %-11s from perturbed: camera %.3f mm (p95 %.3f) / "
                                 "%.3f deg, success %.0f %%",
        c.name.c_str(), name.c_str(), f.cameraPositionMm.median, f.cameraPositionMm.p95,
        f.cameraAngleDeg.median, 100.0 * f.successRate));
    }
    lines.push_back(formatText("P5 %-14s SfM floor %.3f mm / %.3f deg; truth to model %.3f mm; "
                               "%zu sequences failed",
      c.name.c_str(), c.floorPositionMm.median, c.floorAngleDeg.median, c.truthToModelMeanMm,
      c.failedSequences.size()));
  }
  auto percentOf = [](int part, int whole)
  { return whole > 0 ? formatText("%.0f %%", 100.0 * part / whole) : std::string("-"); };
  for (const auto& [method, f] : this->failureFlag())
  {
    lines.push_back(formatText("P5 failure flag %-11s %d registrations pooled: missed %d of %d "
                               "failures (%s), flagged %d of %d good (%s), contour error AUC %s",
      method.c_str(), f.registrations, f.missed, f.failures,
      percentOf(f.missed, f.failures).c_str(), f.falseFlags, f.good,
      percentOf(f.falseFlags, f.good).c_str(),
      f.contourErrorAuc ? formatText("%.3f", *f.contourErrorAuc).c_str() : "-"));
  }
  return lines;
}

} // namespace vimlop
