#include "VideoEvaluation.h"

#include "Error.h"
#include "Rotation.h"

#include <Eigen/Dense>

namespace vimlop
{

/**
 * The true SfM-to-CT similarity from the registered cameras: the rotation is
 * the chordal mean of R_true R_sfmᵀ over the frames (the camera centres of a
 * path along a passage are nearly collinear and leave the roll about it
 * undetermined), then the least-squares scale and translation of the centres.
 */
SimilarityTransform similarityFromCameras(
  const SfmReconstruction& sfm, const std::vector<CameraPose>& truth)
{
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

RegistrationOptions videoRegistrationOptions(
  double initialScale, const VideoEvaluationOptions& o, RegistrationMethod method)
{
  RegistrationOptions options;
  options.method = method;
  options.contourMatch.positionCovariancePx2 = o.contourVariancePx2 * Eigen::Matrix2d::Identity();
  options.contourMatch.kappa = o.kappa;
  options.minScale = initialScale / o.scaleBoundFactor;
  options.maxScale = initialScale * o.scaleBoundFactor;
  options.threads = o.threads;
  options.stallRelativeDecrease = o.stallRelativeDecrease;
  options.stallIterations = o.stallIterations;
  options.maxIterations = o.maxIterations;
  return options;
}

std::vector<SimilarityTransform> canonicalStarts(const RegistrationData& data, double initialScale,
  const std::vector<CameraPose>& posesCT, int* anchorFrame)
{
  // The middle registered frame stands at each canonical pose: the sequence
  // then reaches both ways from it, as the scope moves through the region.
  if (data.frames.empty())
  {
    throw Error("canonical starts: no registered frame");
  }
  const size_t anchor = data.frames.size() / 2;
  if (anchorFrame)
  {
    *anchorFrame = data.frames[anchor].frameId;
  }
  std::vector<SimilarityTransform> starts;
  for (const CameraPose& pose : posesCT)
  {
    starts.push_back(startFromCameraPose(pose, data.frames[anchor].cameraToSfm, initialScale));
  }
  return starts;
}

} // namespace vimlop
