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
 * 0.05 mm², at least 100 000), prepared once with its GICP covariances.
 * Open3D's RegistrationICP builds a k-d tree over the target inside every
 * call (about 70 % of its time on P1), while VIMLOP's search structures are
 * built with the model, outside the timed part; so each method runs two
 * ways: as Open3D's API runs it (`TargetTree::PerCall`), and with the
 * target's tree built once in the constructor (`TargetTree::Prebuilt`),
 * where the same iterations as RegistrationICP's (Open3D's correspondence
 * rule, estimation step and stopping test) run around that tree, its
 * correspondence search on every core as Open3D's. Both give the same
 * estimate, up to the order of sums. One registration at a time: the
 * prebuilt loops share one thread pool.
 */
class Open3DPeers
{
public:
  /// @brief Where the target's k-d tree is built.
  enum class TargetTree
  {
    PerCall, ///< inside every registration, as Open3D's RegistrationICP does
    Prebuilt ///< once, with the peers, like VIMLOP's model
  };

  /// @brief True when VIMLOP was built with Open3D (Debian's libopen3d-dev).
  static bool available();

  /// @throws vimlop::Error when Open3D is not available.
  explicit Open3DPeers(const TriangleMesh& mesh, double maxCorrespondenceMm = 5.0);
  ~Open3DPeers();

  /// @brief Point-to-point ICP estimating a similarity (with scaling).
  SimilarityTransform icpWithScale(const std::vector<Eigen::Vector3d>& points,
    const SimilarityTransform& initial, TargetTree tree = TargetTree::PerCall) const;
  /// @brief Generalized ICP (rigid: Open3D's GICP estimates no scale).
  SimilarityTransform generalizedIcp(const std::vector<Eigen::Vector3d>& points,
    const SimilarityTransform& initial, TargetTree tree = TargetTree::PerCall) const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace vimlop

#endif
