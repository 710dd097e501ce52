#include <vimlop/Video/CameraResection.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Video/SfmGeometry.h>

#include <opencv2/calib3d.hpp>

#include <cmath>

namespace vimlop
{

void CameraResectionOptions::validate() const
{
  if (!(this->thresholdPx > 0.0))
  {
    throw Error(formatText(
      "camera resection: the inlier threshold must be positive, not %g px", this->thresholdPx));
  }
  if (this->iterations < 1)
  {
    throw Error(
      formatText("camera resection: RANSAC needs at least 1 iteration, not %d", this->iterations));
  }
  if (!(this->confidence > 0.0 && this->confidence < 1.0))
  {
    throw Error(formatText(
      "camera resection: the RANSAC confidence must lie in (0, 1), not %g", this->confidence));
  }
}

std::optional<CameraResection> resectCamera(const std::vector<Eigen::Vector3d>& pointsWorld,
  const std::vector<Eigen::Vector2d>& pixels, const PinholeCamera& camera,
  const CameraResectionOptions& options, const CameraPose* guess)
{
  options.validate();
  if (pointsWorld.size() != pixels.size())
  {
    throw Error(
      formatText("camera resection: %zu points but %zu pixels", pointsWorld.size(), pixels.size()));
  }
  const bool fromGuess = options.solver == ResectionSolver::IterativeFromGuess;
  if (fromGuess && !guess)
  {
    throw Error("camera resection: the iterative solver needs a starting pose");
  }
  // EPnP's minimal set is 4 points, and RANSAC needs more to tell inliers.
  if (pointsWorld.size() < 6)
  {
    return std::nullopt;
  }
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  object.reserve(pointsWorld.size());
  image.reserve(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i)
  {
    object.emplace_back(pointsWorld[i].x(), pointsWorld[i].y(), pointsWorld[i].z());
    image.emplace_back(pixels[i].x(), pixels[i].y());
  }
  const cv::Mat k = detail::cameraMatrix(camera);
  cv::Mat rvec;
  cv::Mat tvec;
  if (fromGuess)
  {
    // OpenCV's rotation vector and translation of the world-to-camera map.
    const Eigen::Matrix3d r = guess->rotation.transpose();
    const Eigen::Vector3d t = -r * guess->centre;
    cv::Mat rotation(3, 3, CV_64F);
    for (int row = 0; row < 3; ++row)
    {
      for (int col = 0; col < 3; ++col)
      {
        rotation.at<double>(row, col) = r(row, col);
      }
    }
    cv::Rodrigues(rotation, rvec);
    tvec = (cv::Mat_<double>(3, 1) << t.x(), t.y(), t.z());
  }
  std::vector<int> inliers;
  const bool found = cv::solvePnPRansac(object, image, k, cv::noArray(), rvec, tvec, fromGuess,
    options.iterations, static_cast<float>(options.thresholdPx), options.confidence, inliers,
    fromGuess ? cv::SOLVEPNP_ITERATIVE : cv::SOLVEPNP_EPNP);
  if (!found || inliers.size() < 4)
  {
    return std::nullopt;
  }
  std::vector<cv::Point3d> objectInliers;
  std::vector<cv::Point2d> imageInliers;
  for (int i : inliers)
  {
    objectInliers.push_back(object[static_cast<std::size_t>(i)]);
    imageInliers.push_back(image[static_cast<std::size_t>(i)]);
  }
  cv::solvePnPRefineLM(objectInliers, imageInliers, k, cv::noArray(), rvec, tvec);
  cv::Mat r;
  cv::Rodrigues(rvec, r);
  Eigen::Matrix3d rotation;
  Eigen::Vector3d translation;
  for (int row = 0; row < 3; ++row)
  {
    translation[row] = tvec.at<double>(row);
    for (int col = 0; col < 3; ++col)
    {
      rotation(row, col) = r.at<double>(row, col);
    }
  }
  CameraResection result;
  result.cameraToWorld.rotation = rotation.transpose();
  result.cameraToWorld.centre = -rotation.transpose() * translation;
  result.inliers = std::move(inliers);
  double sum = 0.0;
  for (int i : result.inliers)
  {
    const Eigen::Vector3d c =
      result.cameraToWorld.worldToCamera(pointsWorld[static_cast<std::size_t>(i)]);
    sum +=
      c.z() > 0.0 ? (camera.project(c) - pixels[static_cast<std::size_t>(i)]).squaredNorm() : 1e6;
  }
  result.rmsErrorPx = std::sqrt(sum / static_cast<double>(result.inliers.size()));
  return result;
}

} // namespace vimlop
