#include <vimlop/Core/SimilarityEstimation.h>

#include <vimlop/Core/Error.h>

#include <Eigen/Dense>

#include <algorithm>

namespace vimlop
{

SimilarityTransform estimateSimilarity(const std::vector<Eigen::Vector3d>& source,
  const std::vector<Eigen::Vector3d>& target, double minScale, double maxScale)
{
  if (source.size() != target.size())
  {
    throw Error("similarity estimation: point sets of different sizes");
  }
  if (source.size() < 3)
  {
    throw Error("similarity estimation: at least 3 point pairs are needed");
  }
  const double n = static_cast<double>(source.size());
  Eigen::Vector3d ms = Eigen::Vector3d::Zero();
  Eigen::Vector3d mt = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < source.size(); ++i)
  {
    ms += source[i];
    mt += target[i];
  }
  ms /= n;
  mt /= n;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double sourceVariance = 0.0;
  for (size_t i = 0; i < source.size(); ++i)
  {
    covariance += (target[i] - mt) * (source[i] - ms).transpose();
    sourceVariance += (source[i] - ms).squaredNorm();
  }
  covariance /= n;
  sourceVariance /= n;
  if (!(sourceVariance > 0.0))
  {
    throw Error("similarity estimation: the source points coincide");
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(
    covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d d = Eigen::Vector3d::Ones();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0)
  {
    d[2] = -1.0;
  }
  SimilarityTransform t;
  t.rotation = svd.matrixU() * d.asDiagonal() * svd.matrixV().transpose();
  t.scale = std::clamp(svd.singularValues().dot(d) / sourceVariance, minScale, maxScale);
  t.translation = mt - t.scale * t.rotation * ms;
  return t;
}

} // namespace vimlop
