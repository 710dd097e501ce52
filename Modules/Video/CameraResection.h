#ifndef vimlop_CameraResection_h
#define vimlop_CameraResection_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace vimlop
{

/// @brief How the starting poses of resectCamera()'s RANSAC are found.
enum class ResectionSolver
{
  /// EPnP on each minimal set: no prior pose needed (SfM's registration of a new frame).
  EPnP,
  /// Iterative refinement of each minimal set from the given pose (a
  /// tracker's prediction): steadier when the points barely span depth.
  IterativeFromGuess
};

/// @brief Settings of resectCamera().
struct CameraResectionOptions
{
  /// Reprojection error (px) under which a correspondence is an inlier (default 2).
  double thresholdPx = 2.0;
  /// RANSAC iterations (default 500).
  int iterations = 500;
  /// RANSAC's confidence (default 0.999).
  double confidence = 0.999;
  ResectionSolver solver = ResectionSolver::EPnP;

  /// @throws vimlop::Error naming the first value out of range.
  void validate() const;
};

/// @brief The pose resectCamera() found and the correspondences that agree with it.
struct CameraResection
{
  CameraPose cameraToWorld;
  /// Indices (into the correspondences) of the inliers.
  std::vector<int> inliers;
  /// Root mean square reprojection error of the inliers after the refinement, px.
  double rmsErrorPx = 0.0;
};

/**
 * @brief The camera pose that projects the world points `pointsWorld` (mm)
 * onto `pixels` through the ideal pinhole `camera` (the perspective-n-point
 * problem): RANSAC over minimal sets (OpenCV's solvePnPRansac), then a
 * Levenberg-Marquardt refinement on the inliers. `guess` (camera to world)
 * is required by ResectionSolver::IterativeFromGuess and ignored otherwise.
 * @return Nothing when RANSAC finds no pose (too few points, or none agree).
 * @throws vimlop::Error when the two lists differ in length, for invalid
 * options, or without a guess where one is required.
 */
std::optional<CameraResection> resectCamera(const std::vector<Eigen::Vector3d>& pointsWorld,
  const std::vector<Eigen::Vector2d>& pixels, const PinholeCamera& camera,
  const CameraResectionOptions& options, const CameraPose* guess = nullptr);

} // namespace vimlop

#endif
