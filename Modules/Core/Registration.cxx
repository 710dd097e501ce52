#include "Registration.h"

#include "ChiSquare.h"
#include "Error.h"
#include "KdTree2D.h"
#include "OccludingContours.h"
#include "OutlierRejection.h"
#include "Rotation.h"
#include "SimilarityEstimation.h"
#include "TaskPool.h"

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
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

/// Matches of one frame at one estimate.
struct FrameMatches
{
  std::vector<ModelContourPoint> visibleSamples;
  std::vector<ContourMatch> matches;
  std::vector<char> inliers;
  double contoursMs = 0.0;
  double visibilityMs = 0.0;
  double match2dMs = 0.0;
};

/// Everything matched at one estimate T, with outliers marked.
struct MatchState
{
  std::vector<Eigen::Vector3d> model;     ///< y_i
  std::vector<Eigen::Vector3d> residuals; ///< d_i = y_i - T(x_i)
  std::vector<double> costs;              ///< C3d per point
  std::vector<int> faces;
  std::vector<char> pointInliers;
  std::vector<FrameMatches> frames;
  StageTimes times;
};

class Registrar
{
public:
  Registrar(const RegistrationModel& model, const RegistrationData& data,
    const RegistrationOptions& options)
    : Model(model)
    , Data(data)
    , Options(options)
    , Pool(options.threads)
    , UseContours(options.method == RegistrationMethod::VIMLOP)
    , Constrained(options.anatomicalConstraint && options.method != RegistrationMethod::TrimmedICP)
  {
    const int n3d = static_cast<int>(data.points.size());
    const int n2d = data.numberOfContourPoints();
    // V9: equal influence of the 3-D and 2-D sets whatever their sizes.
    const double factor = this->UseContours && options.equalInfluence && n2d > 0
      ? n3d * (1.0 - options.trimFraction) / n2d
      : 1.0;
    this->Covariances.resize(data.points.size());
    this->Whitenings.resize(data.points.size());
    for (size_t i = 0; i < data.points.size(); ++i)
    {
      this->Covariances[i] = factor * data.pointCovariances[i];
      this->Whitenings[i] = this->Covariances[i].llt().matrixL().solve(Eigen::Matrix3d::Identity());
    }
    this->Hints.assign(data.points.size(), -1);
    this->ChiSquare3 = chiSquareQuantile(options.chiSquareProbability, 3);
    this->Centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& x : data.points)
    {
      this->Centroid += x;
    }
    this->Centroid /= static_cast<double>(data.points.size());
    double spread = 0.0;
    for (const Eigen::Vector3d& x : data.points)
    {
      spread += (x - this->Centroid).squaredNorm();
    }
    this->RadiusMm = std::sqrt(spread / data.points.size());
    this->ContourWhitening =
      options.contourMatch.positionCovariancePx2.llt().matrixL().solve(Eigen::Matrix2d::Identity());
  }

  bool camerasInside(const SimilarityTransform& T, int* outside = nullptr) const
  {
    for (const VideoFrame& frame : this->Data.frames)
    {
      if (!this->Model.isInside(T.apply(frame.cameraToSfm.centre)))
      {
        if (outside)
        {
          *outside = frame.frameId;
        }
        return false;
      }
    }
    return true;
  }

  /// Whether the method uses contours at all.
  bool usesContours() const { return this->UseContours; }

  /// Matches at T; contours only when `withContours` (and the method uses
  /// them, or `measureContours` asks for the contour metrics of any method);
  /// 3-D trimming only when `trim`.
  MatchState match(
    const SimilarityTransform& T, bool withContours, bool trim, bool measureContours = false)
  {
    withContours = (withContours && this->UseContours) ||
      (measureContours && this->Data.numberOfContourPoints() > 0);
    MatchState state;
    const int n = static_cast<int>(this->Data.points.size());
    state.model.resize(n);
    state.residuals.resize(n);
    state.costs.resize(n);
    state.faces.resize(n);

    // V2: 3-D matches, in parallel over fixed chunks.
    auto start = Clock::now();
    const bool icp = this->Options.method == RegistrationMethod::TrimmedICP;
    this->Pool.forChunks(n, 64,
      [&](int begin, int end)
      {
        for (int i = begin; i < end; ++i)
        {
          const Eigen::Vector3d z = T.apply(this->Data.points[i]);
          if (icp)
          {
            const SurfacePoint p = this->Model.tree().closestPoint(z);
            state.model[i] = p.point;
            state.faces[i] = p.face;
            state.costs[i] = 0.5 * (p.point - z).squaredNorm();
          }
          else
          {
            const Eigen::Matrix3d M = T.rotation * this->Covariances[i] * T.rotation.transpose();
            const MostLikelyPoint p = this->Model.tree().mostLikelyPoint(z, M, this->Hints[i]);
            state.model[i] = p.surfacePoint.point;
            state.faces[i] = p.surfacePoint.face;
            state.costs[i] = p.cost;
          }
          state.residuals[i] = state.model[i] - z;
        }
      });
    this->Hints = state.faces;
    state.times.match3dMs = millisecondsSince(start);

    // V3-V5 per frame.
    state.frames.resize(this->Data.frames.size());
    if (withContours)
    {
      auto frameTask = [&](int j) { this->matchFrame(T, j, state.frames[j]); };
      if (this->Model.visibility().isThreadSafe())
      {
        this->Pool.run(static_cast<int>(this->Data.frames.size()), frameTask);
      }
      else
      {
        for (int j = 0; j < static_cast<int>(this->Data.frames.size()); ++j)
        {
          frameTask(j);
        }
      }
      for (const FrameMatches& f : state.frames)
      {
        state.times.contoursMs += f.contoursMs;
        state.times.visibilityMs += f.visibilityMs;
        state.times.match2dMs += f.match2dMs;
      }
    }

    // V8: outliers.
    start = Clock::now();
    state.pointInliers = rejectPointOutliers(state.residuals, this->Covariances, T.rotation,
      state.costs, trim ? this->Options.trimFraction : 0.0,
      icp ? std::numeric_limits<double>::infinity() : this->ChiSquare3);
    if (withContours)
    {
      double sumDistance2 = 0.0;
      double sumAngle2 = 0.0;
      int matched = 0;
      for (const FrameMatches& f : state.frames)
      {
        for (const ContourMatch& m : f.matches)
        {
          if (m.model >= 0)
          {
            sumDistance2 += m.errorPx.squaredNorm();
            sumAngle2 += m.angleRad * m.angleRad;
            ++matched;
          }
        }
      }
      const double meanDistance2 = matched ? sumDistance2 / matched : 0.0;
      const double meanAngle2 = matched ? sumAngle2 / matched : 0.0;
      for (FrameMatches& f : state.frames)
      {
        f.inliers = rejectContourOutliers(f.matches, this->Options.contourMatch, meanDistance2,
          meanAngle2, this->Options.chiSquareProbability, this->Options.maxContourOutlierFraction);
      }
    }
    state.times.outliersMs = millisecondsSince(start);
    return state;
  }

  void matchFrame(const SimilarityTransform& T, int j, FrameMatches& out) const
  {
    const VideoFrame& frame = this->Data.frames[j];
    const CameraPose camera = T.apply(frame.cameraToSfm);
    auto start = Clock::now();
    OccludingContourOptions contourOptions;
    contourOptions.sampleSpacingPx = this->Options.contourSampleSpacingPx;
    std::vector<ModelContourPoint> samples =
      extractOccludingContours(this->Model.mesh(), frame.intrinsics, camera, contourOptions);
    out.contoursMs = millisecondsSince(start);

    start = Clock::now();
    std::vector<Eigen::Vector3d> points(samples.size());
    for (size_t i = 0; i < samples.size(); ++i)
    {
      points[i] = samples[i].point;
    }
    std::vector<char> visible;
    this->Model.visibility().classify(frame.intrinsics, camera, points, visible);
    out.visibleSamples.clear();
    for (size_t i = 0; i < samples.size(); ++i)
    {
      if (visible[i])
      {
        out.visibleSamples.push_back(samples[i]);
      }
    }
    out.visibilityMs = millisecondsSince(start);

    start = Clock::now();
    std::vector<Eigen::Vector2d> pixels(out.visibleSamples.size());
    for (size_t i = 0; i < pixels.size(); ++i)
    {
      pixels[i] = out.visibleSamples[i].pixel;
    }
    const KdTree2D tree(std::move(pixels));
    out.matches =
      matchContours(frame.contour, out.visibleSamples, tree, this->Options.contourMatch);
    out.match2dMs = millisecondsSince(start);
  }

  /// Fills the metrics of an iteration record from a match state.
  void summarise(const MatchState& state, IterationRecord& record) const
  {
    double residual = 0.0;
    for (size_t i = 0; i < state.costs.size(); ++i)
    {
      if (state.pointInliers[i])
      {
        record.cost3d += state.costs[i];
        residual += state.residuals[i].norm();
        ++record.pointInliers;
      }
    }
    record.residualErrorMm = record.pointInliers ? residual / record.pointInliers : 0.0;
    double contourError = 0.0;
    for (const FrameMatches& f : state.frames)
    {
      for (size_t i = 0; i < f.matches.size(); ++i)
      {
        if (f.matches[i].model < 0)
        {
          continue;
        }
        ++record.contourMatches;
        contourError += f.matches[i].errorPx.norm();
        if (f.inliers[i])
        {
          ++record.contourInliers;
          record.cost2d += f.matches[i].cost;
        }
      }
    }
    record.contourErrorPx = record.contourMatches ? contourError / record.contourMatches : 0.0;
    record.cost = record.cost3d + record.cost2d;
    record.times = state.times;
  }

  SimilarityTransform update(const MatchState& state, const SimilarityTransform& T)
  {
    if (this->Options.method == RegistrationMethod::TrimmedICP)
    {
      std::vector<Eigen::Vector3d> source;
      std::vector<Eigen::Vector3d> target;
      for (size_t i = 0; i < state.model.size(); ++i)
      {
        if (state.pointInliers[i])
        {
          source.push_back(this->Data.points[i]);
          target.push_back(state.model[i]);
        }
      }
      if (source.size() < 3)
      {
        return T;
      }
      return estimateSimilarity(source, target, this->Options.minScale, this->Options.maxScale);
    }
    PoseUpdateProblem problem;
    problem.frames = &this->Data.frames;
    problem.kappa = this->Options.contourMatch.kappa;
    problem.contourWhitening = this->ContourWhitening;
    problem.minScale = this->Options.minScale;
    problem.maxScale = this->Options.maxScale;
    for (size_t i = 0; i < state.model.size(); ++i)
    {
      if (state.pointInliers[i])
      {
        problem.points.push_back({ this->Data.points[i], state.model[i], this->Whitenings[i] });
      }
    }
    for (size_t j = 0; j < state.frames.size(); ++j)
    {
      const FrameMatches& f = state.frames[j];
      for (size_t i = 0; i < f.matches.size(); ++i)
      {
        const ContourMatch& m = f.matches[i];
        if (m.model >= 0 && f.inliers[i])
        {
          const ModelContourPoint& y = f.visibleSamples[static_cast<size_t>(m.model)];
          const ContourPoint& x = this->Data.frames[j].contour[i];
          problem.contours.push_back({ static_cast<int>(j), y.point, y.normal, x.pixel, x.normal });
        }
      }
    }
    return solvePoseUpdate(problem, T, this->Options.poseUpdate, &this->Pool).transform;
  }

  /// V10: the update `next` backed off towards `previous` until every camera is inside.
  SimilarityTransform constrain(
    const SimilarityTransform& previous, const SimilarityTransform& next, int& steps) const
  {
    steps = 0;
    if (!this->Constrained || this->camerasInside(next))
    {
      return next;
    }
    const Vector7d change = next.compose(previous.inverse()).log();
    double fraction = 1.0;
    for (steps = 1; steps <= this->Options.maxBackoffSteps; ++steps)
    {
      fraction *= 0.5;
      const SimilarityTransform trial =
        SimilarityTransform::exp(fraction * change).compose(previous);
      if (this->camerasInside(trial))
      {
        return trial;
      }
    }
    return previous;
  }

  /// The change from a to b as displacements in mm: scale and rotation
  /// times the data's radius, and the motion of the data's centroid.
  Vector7d stepInMm(const SimilarityTransform& a, const SimilarityTransform& b) const
  {
    const Vector7d change = b.compose(a.inverse()).log();
    Vector7d step;
    step[0] = this->RadiusMm * change[0];
    step.segment<3>(1) = this->RadiusMm * change.segment<3>(1);
    step.tail<3>() = b.apply(this->Centroid) - a.apply(this->Centroid);
    return step;
  }

  bool converged(const SimilarityTransform& a, const SimilarityTransform& b) const
  {
    const double moved = (b.apply(this->Centroid) - a.apply(this->Centroid)).norm();
    const double rotated = rotationAngleBetween(a.rotation, b.rotation) * 180.0 / M_PI;
    const double scaled = std::abs(b.scale / a.scale - 1.0);
    return moved < this->Options.convergenceTranslationMm &&
      rotated < this->Options.convergenceRotationDeg &&
      scaled < this->Options.convergenceScaleRelative;
  }

  RegistrationResult finish(const SimilarityTransform& T, MatchState state) const
  {
    RegistrationResult result;
    result.sfmToCT = T;
    result.pointInliers = state.pointInliers;
    result.pointMatches = state.model;
    double residual = 0.0;
    int inliers = 0;
    for (size_t i = 0; i < this->Data.points.size(); ++i)
    {
      if (state.pointInliers[i])
      {
        const Eigen::Vector3d z = T.apply(this->Data.points[i]);
        residual += (this->Model.locator().closestPoint(z).point - z).norm();
        ++inliers;
      }
    }
    result.residualErrorMm = inliers ? residual / inliers : 0.0;
    double all = 0.0;
    double in = 0.0;
    int matched = 0;
    int inlierCount = 0;
    for (size_t j = 0; j < this->Data.frames.size(); ++j)
    {
      const VideoFrame& frame = this->Data.frames[j];
      FrameResult fr;
      fr.frameId = frame.frameId;
      fr.cameraToCT = T.apply(frame.cameraToSfm);
      fr.contourPoints = static_cast<int>(frame.contour.size());
      const FrameMatches& f = state.frames[j];
      fr.visibleModelSamples = static_cast<int>(f.visibleSamples.size());
      double frameAll = 0.0;
      double frameIn = 0.0;
      for (size_t i = 0; i < f.matches.size(); ++i)
      {
        const ContourMatch& m = f.matches[i];
        if (m.model < 0)
        {
          continue;
        }
        const ModelContourPoint& y = f.visibleSamples[static_cast<size_t>(m.model)];
        fr.correspondences.push_back(
          { static_cast<int>(i), frame.contour[i].pixel, y.pixel, y.point, f.inliers[i] != 0 });
        ++fr.matched;
        frameAll += m.errorPx.norm();
        if (f.inliers[i])
        {
          ++fr.inliers;
          frameIn += m.errorPx.norm();
        }
      }
      fr.contourErrorPx = fr.matched ? frameAll / fr.matched : 0.0;
      fr.contourErrorInliersPx = fr.inliers ? frameIn / fr.inliers : 0.0;
      all += frameAll;
      in += frameIn;
      matched += fr.matched;
      inlierCount += fr.inliers;
      result.frames.push_back(std::move(fr));
    }
    result.contourErrorPx = matched ? all / matched : 0.0;
    result.contourErrorInliersPx = inlierCount ? in / inlierCount : 0.0;
    return result;
  }

private:
  const RegistrationModel& Model;
  const RegistrationData& Data;
  const RegistrationOptions& Options;
  TaskPool Pool;
  bool UseContours;
  bool Constrained;
  std::vector<Eigen::Matrix3d> Covariances;
  std::vector<Eigen::Matrix3d> Whitenings;
  std::vector<int> Hints;
  double ChiSquare3 = 0.0;
  Eigen::Vector3d Centroid;
  double RadiusMm = 1.0; ///< RMS distance of the data from its centroid (SfM units)
  Eigen::Matrix2d ContourWhitening;
};

/// Match cost per inlier, comparable between iterations whose inlier counts differ.
double meanCost(const IterationRecord& record)
{
  return record.cost3d / std::max(record.pointInliers, 1) +
    record.cost2d / std::max(record.contourInliers, 1);
}

} // namespace

RegistrationResult registerVideo(const RegistrationModel& model, const RegistrationData& data,
  const SimilarityTransform& initialSfmToCT, const RegistrationOptions& options,
  const IterationCallback& callback)
{
  const auto start = Clock::now();
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
  if (options.method == RegistrationMethod::VIMLOP && data.numberOfContourPoints() == 0)
  {
    throw Error(
      "registration: no frame has contour points; V-IMLOP needs them (IMLP registers points only)");
  }
  Registrar registrar(model, data, options);
  if (options.anatomicalConstraint && options.method != RegistrationMethod::TrimmedICP)
  {
    int outside = -1;
    if (!registrar.camerasInside(initialSfmToCT, &outside))
    {
      throw Error("registration: the camera of frame " + std::to_string(outside) +
        " starts outside the model surface; it must start inside the airway");
    }
  }

  SimilarityTransform T = initialSfmToCT;
  std::vector<IterationRecord> history;
  TerminationReason termination = TerminationReason::MaxIterations;
  // Acceleration state: the last un-extrapolated step, and what to return to
  // if an extrapolation turns out worse.
  Vector7d previousStep = Vector7d::Zero();
  bool havePreviousStep = false;
  bool extrapolated = false;
  SimilarityTransform fallback;
  double previousMeanCost = std::numeric_limits<double>::infinity();
  // Stall detection: discrete changes of the match and inlier sets can make
  // the last iterations wander around the solution without settling.
  double bestMeanCost = std::numeric_limits<double>::infinity();
  SimilarityTransform bestTransform = T;
  int iterationsWithoutProgress = 0;
  // Two stages. The first trims 3-D pairs (p_t is the paper's *initial* trim
  // ratio) and, with pointsFirst, leaves the contours out; the second refines
  // with every term and the chi-square tests alone. Trimmed ICP trims always.
  const bool icp = options.method == RegistrationMethod::TrimmedICP;
  bool refining = false;
  bool contoursOn = registrar.usesContours() && !options.pointsFirst;
  auto trimming = [&] { return icp || !refining; };
  // A new stage starts its own convergence, stall and acceleration tracking.
  auto startRefinement = [&]
  {
    refining = true;
    contoursOn = registrar.usesContours();
    havePreviousStep = false;
    extrapolated = false;
    previousMeanCost = std::numeric_limits<double>::infinity();
    bestMeanCost = std::numeric_limits<double>::infinity();
    bestTransform = T;
    iterationsWithoutProgress = 0;
  };
  // Points first: contours join once the points alone have settled.
  for (int iteration = 1; iteration <= options.maxIterations; ++iteration)
  {
    IterationRecord record;
    record.iteration = iteration;
    record.transform = T;
    record.withContours = contoursOn;
    MatchState state = registrar.match(T, contoursOn, trimming());
    registrar.summarise(state, record);
    if (extrapolated && meanCost(record) > previousMeanCost)
    {
      // The extrapolation overshot: return to the plain update.
      T = fallback;
      record = IterationRecord();
      record.iteration = iteration;
      record.transform = T;
      record.withContours = contoursOn;
      record.extrapolationUndone = true;
      state = registrar.match(T, contoursOn, trimming());
      registrar.summarise(state, record);
    }
    extrapolated = false;
    previousMeanCost = meanCost(record);
    if (previousMeanCost < bestMeanCost * (1.0 - options.stallRelativeDecrease))
    {
      bestMeanCost = previousMeanCost;
      bestTransform = T;
      iterationsWithoutProgress = 0;
    }
    else if (++iterationsWithoutProgress >= options.stallIterations)
    {
      record.updated = bestTransform;
      history.push_back(record);
      T = bestTransform;
      if (callback && !callback(history.back()))
      {
        termination = TerminationReason::Cancelled;
        break;
      }
      if (!icp && !refining)
      {
        startRefinement();
        continue;
      }
      termination = TerminationReason::Stalled;
      break;
    }

    auto stageStart = Clock::now();
    SimilarityTransform next = registrar.update(state, T);
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
    next = registrar.constrain(T, next, record.backoffSteps);
    // The first stage also ends at half the iteration budget, so that slow
    // convergence of the points alone never starves the refinement.
    const bool done =
      registrar.converged(T, next) || (!refining && !icp && iteration >= options.maxIterations / 2);

    const Vector7d step = registrar.stepInMm(T, next);
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
      next = registrar.constrain(next, ahead, unused);
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
      if (!icp && !refining)
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
  RegistrationResult result = registrar.finish(T, registrar.match(T, true, trimming(), true));
  result.history = std::move(history);
  result.termination = termination;
  result.iterations = static_cast<int>(result.history.size());
  result.runtimeSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

} // namespace vimlop
