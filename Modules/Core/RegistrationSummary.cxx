#include <vimlop/Core/RegistrationSummary.h>

namespace vimlop
{

void summariseIteration(const Correspondences& matches, IterationRecord& record)
{
  double residual = 0.0;
  for (size_t i = 0; i < matches.costs.size(); ++i)
  {
    if (matches.pointInliers[i])
    {
      record.cost3d += matches.costs[i];
      residual += matches.residuals[i].norm();
      ++record.pointInliers;
    }
  }
  record.residualErrorMm = record.pointInliers ? residual / record.pointInliers : 0.0;
  double contourError = 0.0;
  for (const FrameCorrespondences& f : matches.frames)
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
  record.times = matches.times;
}

RegistrationResult summariseRegistration(const RegistrationModel& model,
  const RegistrationData& data, const SimilarityTransform& T, const Correspondences& matches)
{
  RegistrationResult result;
  result.sfmToCT = T;
  result.pointInliers = matches.pointInliers;
  result.pointMatches = matches.modelPoints;
  double residual = 0.0;
  int inliers = 0;
  for (size_t i = 0; i < data.points.size(); ++i)
  {
    if (matches.pointInliers[i])
    {
      const Eigen::Vector3d z = T.apply(data.points[i]);
      residual += (model.locator().closestPoint(z).point - z).norm();
      ++inliers;
    }
  }
  result.residualErrorMm = inliers ? residual / inliers : 0.0;
  double all = 0.0;
  double in = 0.0;
  int matched = 0;
  int inlierCount = 0;
  for (size_t j = 0; j < data.frames.size(); ++j)
  {
    const VideoFrame& frame = data.frames[j];
    FrameResult fr;
    fr.frameId = frame.frameId;
    fr.cameraToCT = T.apply(frame.cameraToSfm);
    fr.contourPoints = static_cast<int>(frame.contour.size());
    const FrameCorrespondences& f = matches.frames[j];
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

} // namespace vimlop
