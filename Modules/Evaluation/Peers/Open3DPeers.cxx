#include <vimlop/Evaluation/Peers/Open3DPeers.h>

#include <vimlop/Core/Error.h>

#ifdef VIMLOP_HAVE_OPEN3D
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/GeneralizedICP.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>
#include <open3d/utility/Logging.h>
#endif

#include <algorithm>
#include <random>

namespace vimlop
{

#ifdef VIMLOP_HAVE_OPEN3D

namespace registration = open3d::pipelines::registration;

struct Open3DPeers::Internals
{
  open3d::geometry::PointCloud Target;
  double MaxCorrespondenceMm;
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

} // namespace

SimilarityTransform Open3DPeers::icpWithScale(
  const std::vector<Eigen::Vector3d>& points, const SimilarityTransform& initial) const
{
  const registration::RegistrationResult result = registration::RegistrationICP(cloudOf(points),
    this->Impl->Target, this->Impl->MaxCorrespondenceMm, initial.matrix(),
    registration::TransformationEstimationPointToPoint(true), criteria());
  return SimilarityTransform::fromMatrix(result.transformation_, 1e-5);
}

SimilarityTransform Open3DPeers::generalizedIcp(
  const std::vector<Eigen::Vector3d>& points, const SimilarityTransform& initial) const
{
  open3d::geometry::PointCloud source = cloudOf(points);
  source.EstimateCovariances(open3d::geometry::KDTreeSearchParamKNN(20));
  const registration::RegistrationResult result = registration::RegistrationGeneralizedICP(source,
    this->Impl->Target, this->Impl->MaxCorrespondenceMm, initial.matrix(),
    registration::TransformationEstimationForGeneralizedICP(), criteria());
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
  const std::vector<Eigen::Vector3d>&, const SimilarityTransform&) const
{
  throw Error("this build of VIMLOP has no Open3D");
}

SimilarityTransform Open3DPeers::generalizedIcp(
  const std::vector<Eigen::Vector3d>&, const SimilarityTransform&) const
{
  throw Error("this build of VIMLOP has no Open3D");
}

#endif

} // namespace vimlop
