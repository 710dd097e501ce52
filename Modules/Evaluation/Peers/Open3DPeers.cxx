#include <vimlop/Evaluation/Peers/Open3DPeers.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TaskPool.h>

#ifdef VIMLOP_HAVE_OPEN3D
#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/GeneralizedICP.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>
#include <open3d/utility/Logging.h>
#endif

#include <algorithm>
#include <cmath>
#include <random>

namespace vimlop
{

#ifdef VIMLOP_HAVE_OPEN3D

namespace registration = open3d::pipelines::registration;

struct Open3DPeers::Internals
{
  open3d::geometry::PointCloud Target;
  open3d::geometry::KDTreeFlann TargetTree;
  double MaxCorrespondenceMm;
  TaskPool Pool; ///< the prebuilt loops' correspondence search (one registration at a time)
};

bool Open3DPeers::available()
{
  return true;
}

Open3DPeers::Open3DPeers(const TriangleMesh& mesh, double maxCorrespondenceMm)
  : Impl(std::make_unique<Internals>())
{
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
  this->Impl->MaxCorrespondenceMm = maxCorrespondenceMm;
  const int samples = std::max(100000, static_cast<int>(mesh.totalArea() / 0.05));
  std::vector<double> cumulative(static_cast<size_t>(mesh.numberOfFaces()));
  double area = 0.0;
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    area += mesh.faceAreas()[f];
    cumulative[f] = area;
  }
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  this->Impl->Target.points_.reserve(static_cast<size_t>(samples));
  for (int i = 0; i < samples; ++i)
  {
    const int f = std::min(mesh.numberOfFaces() - 1,
      static_cast<int>(std::lower_bound(cumulative.begin(), cumulative.end(), u(rng) * area) -
        cumulative.begin()));
    double a = u(rng);
    double b = u(rng);
    if (a + b > 1.0)
    {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    this->Impl->Target.points_.push_back(mesh.corner(f, 0) +
      a * (mesh.corner(f, 1) - mesh.corner(f, 0)) + b * (mesh.corner(f, 2) - mesh.corner(f, 0)));
  }
  this->Impl->Target.EstimateCovariances(open3d::geometry::KDTreeSearchParamKNN(20));
  this->Impl->TargetTree.SetGeometry(this->Impl->Target);
}

Open3DPeers::~Open3DPeers() = default;

namespace
{

open3d::geometry::PointCloud cloudOf(const std::vector<Eigen::Vector3d>& points)
{
  open3d::geometry::PointCloud cloud;
  cloud.points_ = points;
  return cloud;
}

registration::ICPConvergenceCriteria criteria()
{
  return registration::ICPConvergenceCriteria(1e-7, 1e-7, 100);
}

/// Open3D's correspondences (each moved source point's nearest target point
/// within the distance), fitness and inlier RMSE at `transformation`, in
/// parallel like Open3D's own (which uses OpenMP), in source order.
registration::RegistrationResult matchToTarget(const open3d::geometry::PointCloud& moved,
  const open3d::geometry::KDTreeFlann& tree, double maxDistance,
  const Eigen::Matrix4d& transformation, TaskPool& pool)
{
  const int n = static_cast<int>(moved.points_.size());
  std::vector<int> nearest(static_cast<size_t>(n), -1);
  std::vector<double> nearest2(static_cast<size_t>(n), 0.0);
  pool.forChunks(n, 256,
    [&](int begin, int end)
    {
      std::vector<int> index(1);
      std::vector<double> distance2(1);
      for (int i = begin; i < end; ++i)
      {
        if (tree.SearchHybrid(moved.points_[i], maxDistance, 1, index, distance2) > 0)
        {
          nearest[i] = index[0];
          nearest2[i] = distance2[0];
        }
      }
    });
  registration::RegistrationResult result(transformation);
  double error2 = 0.0;
  for (int i = 0; i < n; ++i)
  {
    if (nearest[i] >= 0)
    {
      result.correspondence_set_.emplace_back(i, nearest[i]);
      error2 += nearest2[i];
    }
  }
  const size_t matched = result.correspondence_set_.size();
  result.fitness_ = n > 0 ? static_cast<double>(matched) / n : 0.0;
  result.inlier_rmse_ = matched > 0 ? std::sqrt(error2 / static_cast<double>(matched)) : 0.0;
  return result;
}

/// The iterations of Open3D's RegistrationICP around a tree built beforehand.
registration::RegistrationResult iterateWithPrebuiltTree(const open3d::geometry::PointCloud& source,
  const open3d::geometry::PointCloud& target, const open3d::geometry::KDTreeFlann& tree,
  double maxDistance, const Eigen::Matrix4d& initial,
  const registration::TransformationEstimation& estimation,
  const registration::ICPConvergenceCriteria& stop, TaskPool& pool)
{
  Eigen::Matrix4d transformation = initial;
  open3d::geometry::PointCloud moved = source;
  moved.Transform(initial);
  registration::RegistrationResult result =
    matchToTarget(moved, tree, maxDistance, transformation, pool);
  for (int iteration = 0; iteration < stop.max_iteration_; ++iteration)
  {
    const Eigen::Matrix4d update =
      estimation.ComputeTransformation(moved, target, result.correspondence_set_);
    transformation = update * transformation;
    moved.Transform(update);
    const registration::RegistrationResult previous = result;
    result = matchToTarget(moved, tree, maxDistance, transformation, pool);
    if (std::abs(previous.fitness_ - result.fitness_) < stop.relative_fitness_ &&
      std::abs(previous.inlier_rmse_ - result.inlier_rmse_) < stop.relative_rmse_)
    {
      break;
    }
  }
  return result;
}

} // namespace

SimilarityTransform Open3DPeers::icpWithScale(const std::vector<Eigen::Vector3d>& points,
  const SimilarityTransform& initial, TargetTree tree) const
{
  const registration::TransformationEstimationPointToPoint estimation(true);
  const registration::RegistrationResult result = tree == TargetTree::PerCall
    ? registration::RegistrationICP(cloudOf(points), this->Impl->Target,
        this->Impl->MaxCorrespondenceMm, initial.matrix(), estimation, criteria())
    : iterateWithPrebuiltTree(cloudOf(points), this->Impl->Target, this->Impl->TargetTree,
        this->Impl->MaxCorrespondenceMm, initial.matrix(), estimation, criteria(),
        this->Impl->Pool);
  return SimilarityTransform::fromMatrix(result.transformation_, 1e-5);
}

SimilarityTransform Open3DPeers::generalizedIcp(const std::vector<Eigen::Vector3d>& points,
  const SimilarityTransform& initial, TargetTree tree) const
{
  open3d::geometry::PointCloud source = cloudOf(points);
  source.EstimateCovariances(open3d::geometry::KDTreeSearchParamKNN(20));
  const registration::TransformationEstimationForGeneralizedICP estimation;
  const registration::RegistrationResult result = tree == TargetTree::PerCall
    ? registration::RegistrationGeneralizedICP(source, this->Impl->Target,
        this->Impl->MaxCorrespondenceMm, initial.matrix(), estimation, criteria())
    : iterateWithPrebuiltTree(source, this->Impl->Target, this->Impl->TargetTree,
        this->Impl->MaxCorrespondenceMm, initial.matrix(), estimation, criteria(),
        this->Impl->Pool);
  return SimilarityTransform::fromMatrix(result.transformation_, 1e-5);
}

#else

struct Open3DPeers::Internals
{
};

bool Open3DPeers::available()
{
  return false;
}

Open3DPeers::Open3DPeers(const TriangleMesh&, double)
{
  throw Error("this build of VIMLOP has no Open3D (install libopen3d-dev and rebuild)");
}

Open3DPeers::~Open3DPeers() = default;

SimilarityTransform Open3DPeers::icpWithScale(
  const std::vector<Eigen::Vector3d>&, const SimilarityTransform&, TargetTree) const
{
  throw Error("this build of VIMLOP has no Open3D");
}

SimilarityTransform Open3DPeers::generalizedIcp(
  const std::vector<Eigen::Vector3d>&, const SimilarityTransform&, TargetTree) const
{
  throw Error("this build of VIMLOP has no Open3D");
}

#endif

} // namespace vimlop
