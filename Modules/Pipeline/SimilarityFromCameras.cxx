#include <vimlop/Pipeline/SimilarityFromCameras.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <string>

namespace vimlop
{

SimilarityTransform similarityFromCameras(
  const SfmReconstruction& sfm, const std::vector<CameraPose>& truth)
{
  if (truth.size() != sfm.frames.size())
  {
    throw Error("similarity from cameras: " + std::to_string(truth.size()) + " poses for " +
      std::to_string(sfm.frames.size()) + " SfM frames");
  }
  if (sfm.numberOfRegisteredFrames() < 2)
  {
    throw Error("similarity from cameras: needs at least two registered frames");
  }
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  Eigen::Vector3d meanSfm = Eigen::Vector3d::Zero();
  Eigen::Vector3d meanCT = Eigen::Vector3d::Zero();
  int n = 0;
  for (size_t f = 0; f < sfm.frames.size(); ++f)
  {
    if (sfm.frames[f].registered)
    {
      sum += truth[f].rotation * sfm.frames[f].cameraToSfm.rotation.transpose();
      meanSfm += sfm.frames[f].cameraToSfm.centre;
      meanCT += truth[f].centre;
      ++n;
    }
  }
  meanSfm /= n;
  meanCT /= n;
  SimilarityTransform t;
  t.rotation = nearestRotation(sum);
  double numerator = 0.0;
  double denominator = 0.0;
  for (size_t f = 0; f < sfm.frames.size(); ++f)
  {
    if (sfm.frames[f].registered)
    {
      const Eigen::Vector3d a = t.rotation * (sfm.frames[f].cameraToSfm.centre - meanSfm);
      numerator += (truth[f].centre - meanCT).dot(a);
      denominator += a.squaredNorm();
    }
  }
  t.scale = numerator / denominator;
  t.translation = meanCT - t.scale * t.rotation * meanSfm;
  return t;
}

} // namespace vimlop
