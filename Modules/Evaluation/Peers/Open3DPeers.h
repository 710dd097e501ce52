#ifndef vimlop_Open3DPeers_h
#define vimlop_Open3DPeers_h

#include <vimlop/Core/SimilarityTransform.h>
#include <vimlop/Core/TriangleMesh.h>

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace vimlop
{

/**
 * @brief Open3D's registration methods as peers of the evaluation protocols:
 * point-to-point ICP with scale and generalized ICP (rigid), run on the same
 * SfM points from the same start as VIMLOP's methods.
 *
 * The target is the model surface sampled uniformly by area (one point per
 * 0.05 mm², at least 100 000), prepared once with its k-d tree and GICP
 * covariances so that per-trial runtimes compare like with like.
 */
class Open3DPeers
{
public:
  /// @brief True when VIMLOP was built with Open3D (Debian's libopen3d-dev).
  static bool available();

  /// @throws vimlop::Error when Open3D is not available.
  explicit Open3DPeers(const TriangleMesh& mesh, double maxCorrespondenceMm = 5.0);
  ~Open3DPeers();

  /// @brief Point-to-point ICP estimating a similarity (with scaling).
  SimilarityTransform icpWithScale(
    const std::vector<Eigen::Vector3d>& points, const SimilarityTransform& initial) const;
  /// @brief Generalized ICP (rigid: Open3D's GICP estimates no scale).
  SimilarityTransform generalizedIcp(
    const std::vector<Eigen::Vector3d>& points, const SimilarityTransform& initial) const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace vimlop

#endif
