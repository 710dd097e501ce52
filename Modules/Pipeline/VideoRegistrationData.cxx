#include <vimlop/Pipeline/VideoRegistrationData.h>

#include <vimlop/Core/Error.h>

#include <cmath>
#include <string>

namespace vimlop
{

RegistrationData makeVideoRegistrationData(const SfmReconstruction& sfm,
  const std::vector<std::vector<ContourPoint>>& contoursPerFrame, double initialScale,
  double pointNoiseFloorMm, std::vector<int>* frameOf, const std::vector<int>* frameIds)
{
  if (contoursPerFrame.size() != sfm.frames.size())
  {
    throw Error("registration data: " + std::to_string(contoursPerFrame.size()) +
      " contour lists for " + std::to_string(sfm.frames.size()) + " SfM frames");
  }
  if (frameIds && frameIds->size() != sfm.frames.size())
  {
    throw Error("registration data: " + std::to_string(frameIds->size()) + " frame ids for " +
      std::to_string(sfm.frames.size()) + " SfM frames");
  }
  if (!(initialScale > 0.0) || !std::isfinite(initialScale))
  {
    throw Error("registration data: the initial scale must be a positive number, got " +
      std::to_string(initialScale));
  }
  if (!(pointNoiseFloorMm >= 0.0) || !std::isfinite(pointNoiseFloorMm))
  {
    throw Error("registration data: the point noise floor must be a non-negative number of mm");
  }
  RegistrationData data;
  if (frameOf)
  {
    frameOf->clear();
  }
  for (size_t f = 0; f < sfm.frames.size(); ++f)
  {
    if (!sfm.frames[f].registered)
    {
      continue;
    }
    VideoFrame frame;
    frame.frameId = frameIds ? (*frameIds)[f] : static_cast<int>(f);
    frame.intrinsics = sfm.frames[f].intrinsics;
    frame.intrinsics.removeDistortion();
    frame.cameraToSfm = sfm.frames[f].cameraToSfm;
    frame.contour = contoursPerFrame[f];
    data.frames.push_back(frame);
    if (frameOf)
    {
      frameOf->push_back(static_cast<int>(f));
    }
  }
  const double s2 = initialScale * initialScale;
  const double floor2 = pointNoiseFloorMm * pointNoiseFloorMm;
  for (const SfmReconstruction::Point& p : sfm.points)
  {
    data.points.push_back(p.position);
    data.pointCovariances.push_back(s2 * p.covariance + floor2 * Eigen::Matrix3d::Identity());
  }
  return data;
}

} // namespace vimlop
