#include <vimlop/Video/SfmGeometry.h>

#include <Eigen/Dense>

namespace vimlop::detail
{

cv::Mat cameraMatrix(const PinholeCamera& k)
{
  return (cv::Mat_<double>(3, 3) << k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
}

Eigen::Vector2d pixelOf(const cv::KeyPoint& k)
{
  return { k.pt.x, k.pt.y };
}

Eigen::Matrix<double, 3, 4> projectionOf(const CameraPose& pose)
{
  Eigen::Matrix<double, 3, 4> p;
  p.leftCols<3>() = pose.rotation.transpose();
  p.col(3) = -pose.rotation.transpose() * pose.centre;
  return p;
}

Eigen::Vector3d triangulate(const std::vector<Eigen::Matrix<double, 3, 4>>& projections,
  const std::vector<Eigen::Vector2d>& normalised)
{
  Eigen::MatrixXd a(2 * projections.size(), 4);
  for (size_t k = 0; k < projections.size(); ++k)
  {
    a.row(2 * k) = normalised[k].x() * projections[k].row(2) - projections[k].row(0);
    a.row(2 * k + 1) = normalised[k].y() * projections[k].row(2) - projections[k].row(1);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  const Eigen::Vector4d x = svd.matrixV().col(3);
  return x.head<3>() / x[3];
}

} // namespace vimlop::detail
