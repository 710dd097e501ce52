#include <vimlop/Core/CorrespondenceSearch.h>

#include <vimlop/Core/ChiSquare.h>
#include <vimlop/Core/KdTree2D.h>
#include <vimlop/Core/OutlierRejection.h>
#include <vimlop/Core/TaskPool.h>
#include <vimlop/Core/VisibleModelContours.h>

#include <Eigen/Cholesky>

#include <chrono>
#include <limits>

namespace vimlop
{

namespace
{

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

} // namespace

CorrespondenceSearch::CorrespondenceSearch(const RegistrationModel& model,
  const RegistrationData& data, const RegistrationOptions& options, TaskPool& pool)
  : Model(model)
  , Data(data)
  , Options(options)
  , Pool(pool)
  , Method(describeMethod(options.method))
{
  const int n3d = static_cast<int>(data.points.size());
  const int n2d = data.numberOfContourPoints();
  // V9: equal influence of the 3-D and 2-D sets whatever their sizes.
  const double factor = this->Method.usesContours && options.equalInfluence && n2d > 0
    ? n3d * (1.0 - options.trimFraction) / n2d
    : 1.0;
  this->Covariances.resize(data.points.size());
  for (size_t i = 0; i < data.points.size(); ++i)
  {
    this->Covariances[i] = factor * data.pointCovariances[i];
  }
  this->Hints.assign(data.points.size(), -1);
  this->ChiSquare3 = this->Method.chiSquareTest ? chiSquareQuantile(options.chiSquareProbability, 3)
                                                : std::numeric_limits<double>::infinity();
}

Correspondences CorrespondenceSearch::find(
  const SimilarityTransform& T, bool withContours, bool trim)
{
  Correspondences c;
  const int n = static_cast<int>(this->Data.points.size());
  c.modelPoints.resize(n);
  c.residuals.resize(n);
  c.costs.resize(n);
  c.faces.resize(n);

  // V2: 3-D matches, in parallel over fixed chunks.
  auto start = Clock::now();
  const bool closest = this->Method.pointMatching == PointMatching::ClosestPoint;
  this->Pool.forChunks(n, 64,
    [&](int begin, int end)
    {
      for (int i = begin; i < end; ++i)
      {
        const Eigen::Vector3d z = T.apply(this->Data.points[i]);
        if (closest)
        {
          const SurfacePoint p = this->Model.tree().closestPoint(z);
          c.modelPoints[i] = p.point;
          c.faces[i] = p.face;
          c.costs[i] = 0.5 * (p.point - z).squaredNorm();
        }
        else
        {
          const Eigen::Matrix3d M = T.rotation * this->Covariances[i] * T.rotation.transpose();
          const MostLikelyPoint p = this->Model.tree().mostLikelyPoint(z, M, this->Hints[i]);
          c.modelPoints[i] = p.surfacePoint.point;
          c.faces[i] = p.surfacePoint.face;
          c.costs[i] = p.cost;
        }
        c.residuals[i] = c.modelPoints[i] - z;
      }
    });
  this->Hints = c.faces;
  c.times.match3dMs = millisecondsSince(start);

  // V3-V5 per frame.
  c.frames.resize(this->Data.frames.size());
  if (withContours)
  {
    auto frameTask = [&](int j) { this->matchFrame(T, j, c.frames[j]); };
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
    for (const FrameCorrespondences& f : c.frames)
    {
      c.times.contoursMs += f.times.contoursMs;
      c.times.visibilityMs += f.times.visibilityMs;
      c.times.match2dMs += f.times.match2dMs;
    }
  }

  start = Clock::now();
  this->rejectOutliers(T, withContours, trim, c);
  c.times.outliersMs = millisecondsSince(start);
  return c;
}

void CorrespondenceSearch::matchFrame(
  const SimilarityTransform& T, int j, FrameCorrespondences& out) const
{
  const VideoFrame& frame = this->Data.frames[j];
  OccludingContourOptions contourOptions;
  contourOptions.sampleSpacingPx = this->Options.contourSampleSpacingPx;
  out.visibleSamples = visibleModelContours(
    this->Model, frame.intrinsics, T.apply(frame.cameraToSfm), contourOptions, &out.times);

  const auto start = Clock::now();
  std::vector<Eigen::Vector2d> pixels(out.visibleSamples.size());
  for (size_t i = 0; i < pixels.size(); ++i)
  {
    pixels[i] = out.visibleSamples[i].pixel;
  }
  const KdTree2D tree(std::move(pixels));
  out.matches = matchContours(frame.contour, out.visibleSamples, tree, this->Options.contourMatch);
  out.times.match2dMs = millisecondsSince(start);
}

void CorrespondenceSearch::rejectOutliers(
  const SimilarityTransform& T, bool withContours, bool trim, Correspondences& c) const
{
  // V8: 3-D pairs, then each frame's contour pairs with the variance
  // inflation of every frame's current matches.
  c.pointInliers = rejectPointOutliers(c.residuals, this->Covariances, T.rotation, c.costs,
    trim ? this->Options.trimFraction : 0.0, this->ChiSquare3);
  if (!withContours)
  {
    return;
  }
  const ContourErrorSpread spread =
    contourErrorSpread(c.frames, this->Options.robustContourInflation);
  for (FrameCorrespondences& f : c.frames)
  {
    f.inliers = rejectContourOutliers(f.matches, this->Options.contourMatch,
      spread.squaredDistancePx2, spread.squaredAngleRad2, this->Options.chiSquareProbability,
      this->Options.maxContourOutlierFraction);
  }
}

} // namespace vimlop
