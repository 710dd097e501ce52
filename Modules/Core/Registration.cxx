#include <vimlop/Core/Registration.h>

#include <vimlop/Core/AnatomicalConstraint.h>
#include <vimlop/Core/ClosedFormSimilarityEstimator.h>
#include <vimlop/Core/ConvergenceCriteria.h>
#include <vimlop/Core/CorrespondenceSearch.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/LevenbergMarquardtPoseEstimator.h>
#include <vimlop/Core/MethodDescriptor.h>
#include <vimlop/Core/RegistrationSummary.h>
#include <vimlop/Core/TaskPool.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace vimlop
{

const char* toString(TerminationReason reason)
{
  switch (reason)
  {
    case TerminationReason::Converged:
      return "converged";
    case TerminationReason::Stalled:
      return "stalled";
    case TerminationReason::MaxIterations:
      return "max-iterations";
    case TerminationReason::Cancelled:
      return "cancelled";
    case TerminationReason::NumericalFailure:
      return "numerical-failure";
  }
  return "unknown";
}

namespace
{

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void checkInput(const RegistrationModel& model, const RegistrationData& data,
  const SimilarityTransform& initialSfmToCT, const RegistrationOptions& options)
{
  options.validate();
  data.validate();
  if (!initialSfmToCT.isValid())
  {
    throw Error("registration: the initial transform is not a valid similarity");
  }
  if (initialSfmToCT.scale < options.minScale || initialSfmToCT.scale > options.maxScale)
  {
    throw Error("registration: the initial scale " + std::to_string(initialSfmToCT.scale) +
      " lies outside the scale bounds [" + std::to_string(options.minScale) + ", " +
      std::to_string(options.maxScale) + "]");
  }
  if (describeMethod(options.method).usesContours && data.numberOfContourPoints() == 0)
  {
    throw Error(
      "registration: no frame has contour points; V-IMLOP needs them (IMLP registers points only)");
  }
  int outside = -1;
  if (usesAnatomicalConstraint(options) &&
    !camerasInside(model, data.frames, initialSfmToCT, &outside))
  {
    throw Error("registration: the camera of frame " + std::to_string(outside) +
      " starts outside the model surface; it must start inside the airway");
  }
}

std::unique_ptr<PoseEstimator> makePoseEstimator(PoseEstimation estimation,
  const CorrespondenceSearch& search, const RegistrationOptions& options, TaskPool& pool)
{
  if (estimation == PoseEstimation::ClosedFormSimilarity)
  {
    return std::make_unique<ClosedFormSimilarityEstimator>(options.minScale, options.maxScale);
  }
  return std::make_unique<LevenbergMarquardtPoseEstimator>(search.covariances(), options, &pool);
}

} // namespace

RegistrationResult registerVideo(const RegistrationModel& model, const RegistrationData& data,
  const SimilarityTransform& initialSfmToCT, const RegistrationOptions& options,
  const IterationCallback& callback)
{
  const auto start = Clock::now();
  checkInput(model, data, initialSfmToCT, options);
  const MethodDescriptor method = describeMethod(options.method);
  const bool constrained = usesAnatomicalConstraint(options);
  const bool twoStages = method.trimming == TrimSchedule::FirstStageOnly;
  TaskPool pool(options.threads);
  CorrespondenceSearch search(model, data, options, pool);
  const std::unique_ptr<PoseEstimator> estimator =
    makePoseEstimator(method.poseEstimation, search, options, pool);
  ConvergenceCriteria criteria(data.points, options);
  // V10, or the update as it is when the constraint is off.
  auto constrain =
    [&](const SimilarityTransform& previous, const SimilarityTransform& next, int& steps)
  {
    steps = 0;
    return constrained
      ? backOffIntoAirway(model, data.frames, previous, next, options.maxBackoffSteps, steps)
      : next;
  };

  SimilarityTransform T = initialSfmToCT;
  criteria.restartStallTracking(T);
  std::vector<IterationRecord> history;
  TerminationReason termination = TerminationReason::MaxIterations;
  // Acceleration state: the last un-extrapolated step, and what to return to
  // if an extrapolation turns out worse.
  Vector7d previousStep = Vector7d::Zero();
  bool havePreviousStep = false;
  bool extrapolated = false;
  SimilarityTransform fallback;
  double previousMeanCost = std::numeric_limits<double>::infinity();
  // Two stages, unless the method trims throughout. The first trims 3-D pairs
  // (p_t is the paper's *initial* trim ratio) and, with pointsFirst, leaves
  // the contours out; the second refines with every term and the chi-square
  // tests alone.
  bool refining = false;
  bool contoursOn = method.usesContours && !options.pointsFirst;
  auto trimming = [&] { return !twoStages || !refining; };
  // A new stage starts its own convergence, stall and acceleration tracking.
  auto startRefinement = [&]
  {
    refining = true;
    contoursOn = method.usesContours;
    havePreviousStep = false;
    extrapolated = false;
    previousMeanCost = std::numeric_limits<double>::infinity();
    criteria.restartStallTracking(T);
  };
  auto matchAndRecord = [&](int iteration, IterationRecord& record, Correspondences& matches)
  {
    record.iteration = iteration;
    record.transform = T;
    record.withContours = contoursOn;
    matches = search.find(T, contoursOn, trimming());
    summariseIteration(matches, record);
  };
  for (int iteration = 1; iteration <= options.maxIterations; ++iteration)
  {
    IterationRecord record;
    Correspondences matches;
    matchAndRecord(iteration, record, matches);
    if (extrapolated && meanMatchCost(record) > previousMeanCost)
    {
      // The extrapolation overshot: return to the plain update.
      T = fallback;
      record = IterationRecord();
      record.extrapolationUndone = true;
      matchAndRecord(iteration, record, matches);
    }
    extrapolated = false;
    previousMeanCost = meanMatchCost(record);
    if (criteria.stalled(previousMeanCost, T))
    {
      record.updated = criteria.bestTransform();
      history.push_back(record);
      T = criteria.bestTransform();
      if (callback && !callback(history.back()))
      {
        termination = TerminationReason::Cancelled;
        break;
      }
      if (twoStages && !refining)
      {
        startRefinement();
        continue;
      }
      termination = TerminationReason::Stalled;
      break;
    }

    auto stageStart = Clock::now();
    SimilarityTransform next = estimator->estimate(data, matches, T);
    record.times.updateMs = millisecondsSince(stageStart);
    if (!next.isValid(1e-6))
    {
      termination = TerminationReason::NumericalFailure;
      record.updated = T;
      history.push_back(record);
      if (callback)
      {
        callback(history.back());
      }
      break;
    }
    stageStart = Clock::now();
    next = constrain(T, next, record.backoffSteps);
    // The first stage also ends at half the iteration budget, so that slow
    // convergence of the points alone never starves the refinement.
    const bool done = criteria.converged(T, next) ||
      (twoStages && !refining && iteration >= options.maxIterations / 2);

    const Vector7d step = criteria.stepInMm(T, next);
    const double angle = std::acos(std::clamp(
      step.dot(previousStep) / std::max(step.norm() * previousStep.norm(), 1e-300), -1.0, 1.0));
    const double ratio = step.norm() / std::max(previousStep.norm(), 1e-300);
    if (options.accelerate && !done && havePreviousStep && angle < 10.0 * M_PI / 180.0 &&
      ratio < 1.0)
    {
      // Besl-McKay: steps shrinking geometrically along one direction sum to
      // ratio / (1 - ratio) more of the last one.
      record.acceleration = std::min(ratio / (1.0 - ratio), options.maxAcceleration);
      const SimilarityTransform ahead =
        SimilarityTransform::exp(record.acceleration * next.compose(T.inverse()).log())
          .compose(next);
      int unused = 0;
      fallback = next;
      next = constrain(next, ahead, unused);
      extrapolated = true;
      havePreviousStep = false;
    }
    else
    {
      previousStep = step;
      havePreviousStep = true;
    }
    record.times.constraintMs = millisecondsSince(stageStart);
    record.updated = next;
    history.push_back(record);

    T = next;
    if (callback && !callback(history.back()))
    {
      termination = TerminationReason::Cancelled;
      break;
    }
    if (done)
    {
      if (twoStages && !refining)
      {
        startRefinement();
        continue;
      }
      termination = TerminationReason::Converged;
      break;
    }
  }

  // The contour metrics of the result (V12) are measured for every method,
  // so that baselines can be compared and a multi-start can rank them.
  RegistrationResult result = summariseRegistration(
    model, data, T, search.find(T, data.numberOfContourPoints() > 0, trimming()));
  result.history = std::move(history);
  result.termination = termination;
  result.iterations = static_cast<int>(result.history.size());
  result.runtimeSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

} // namespace vimlop
