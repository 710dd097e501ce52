#include <vimlop/Video/BundleAdjustment.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <Eigen/Dense>

#include <cmath>

namespace vimlop
{

namespace
{

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix63d = Eigen::Matrix<double, 6, 3>;

struct State
{
  std::vector<Eigen::Matrix3d> rotation; ///< world to camera
  std::vector<Eigen::Vector3d> translation;
  std::vector<Eigen::Vector3d> points;
};

double huberCost(double squared, double delta)
{
  const double s = std::sqrt(squared);
  return s <= delta ? squared : 2.0 * delta * s - delta * delta;
}

/// Robust cost and plain sum of squared errors over the observations.
void evaluate(const State& x, const std::vector<PinholeCamera>& k,
  const std::vector<BundleAdjustment::Observation>& observations, double delta, double& cost,
  double& squares)
{
  cost = 0.0;
  squares = 0.0;
  for (const BundleAdjustment::Observation& o : observations)
  {
    const Eigen::Vector3d c = x.rotation[o.camera] * x.points[o.point] + x.translation[o.camera];
    double e2 = 0.0;
    if (c.z() > 1e-12)
    {
      e2 = (k[o.camera].project(c) - o.pixel).squaredNorm();
    }
    else
    {
      // Behind the camera: a large, finite penalty that any update fixing it beats.
      e2 = 1e6;
    }
    cost += huberCost(e2, delta);
    squares += e2;
  }
}

} // namespace

BundleAdjustment::Summary BundleAdjustment::adjust(std::vector<CameraPose>& cameras,
  std::vector<Eigen::Vector3d>& points, const std::vector<PinholeCamera>& intrinsics,
  const std::vector<Observation>& observations, const std::vector<int>& fixedCameras,
  const BundleAdjustmentOptions& options)
{
  const int m = static_cast<int>(cameras.size());
  const int n = static_cast<int>(points.size());
  if (static_cast<int>(intrinsics.size()) != m)
  {
    throw Error("bundle adjustment: one set of intrinsics per camera is needed");
  }
  for (const Observation& o : observations)
  {
    if (o.camera < 0 || o.camera >= m || o.point < 0 || o.point >= n)
    {
      throw Error(
        "bundle adjustment: an observation refers to a camera or point that does not exist");
    }
  }
  std::vector<int> block(static_cast<size_t>(m), 0);
  for (int f : fixedCameras)
  {
    if (f < 0 || f >= m)
    {
      throw Error("bundle adjustment: fixed camera " + std::to_string(f) + " does not exist");
    }
    block[f] = -1;
  }
  int freeCameras = 0;
  for (int j = 0; j < m; ++j)
  {
    if (block[j] == 0)
    {
      block[j] = freeCameras++;
    }
  }

  State x;
  for (const CameraPose& c : cameras)
  {
    x.rotation.push_back(c.rotation.transpose());
    x.translation.push_back(-c.rotation.transpose() * c.centre);
  }
  x.points = points;
  std::vector<std::vector<int>> observationsOf(static_cast<size_t>(n));
  for (size_t a = 0; a < observations.size(); ++a)
  {
    observationsOf[observations[a].point].push_back(static_cast<int>(a));
  }

  const double delta = options.huberPx;
  Summary summary;
  double cost = 0.0;
  double squares = 0.0;
  evaluate(x, intrinsics, observations, delta, cost, squares);
  summary.initialRmsPx = observations.empty() ? 0.0 : std::sqrt(squares / observations.size());
  double lambda = options.initialDamping;

  std::vector<Matrix6d> U(static_cast<size_t>(m));
  std::vector<Vector6d> gc(static_cast<size_t>(m));
  std::vector<Eigen::Matrix3d> V(static_cast<size_t>(n));
  std::vector<Eigen::Vector3d> gp(static_cast<size_t>(n));
  std::vector<Matrix63d> W(observations.size());
  const int dimension = 6 * freeCameras;
  int scaleParameter = -1;
  if (options.scaleCamera >= 0 && options.scaleCamera < m && block[options.scaleCamera] >= 0)
  {
    Eigen::Index axis = 0;
    x.translation[options.scaleCamera].cwiseAbs().maxCoeff(&axis);
    scaleParameter = 6 * block[options.scaleCamera] + 3 + static_cast<int>(axis);
  }

  for (int iteration = 0; iteration < options.maxIterations; ++iteration)
  {
    // Normal equations of the reweighted Gauss-Newton model.
    std::fill(U.begin(), U.end(), Matrix6d::Zero());
    std::fill(gc.begin(), gc.end(), Vector6d::Zero());
    std::fill(V.begin(), V.end(), Eigen::Matrix3d::Zero());
    std::fill(gp.begin(), gp.end(), Eigen::Vector3d::Zero());
    for (size_t a = 0; a < observations.size(); ++a)
    {
      const Observation& o = observations[a];
      const Eigen::Vector3d rotated = x.rotation[o.camera] * x.points[o.point];
      const Eigen::Vector3d c = rotated + x.translation[o.camera];
      W[a].setZero();
      if (c.z() <= 1e-12)
      {
        continue;
      }
      const PinholeCamera& k = intrinsics[o.camera];
      const Eigen::Vector2d r = k.project(c) - o.pixel;
      const double norm = r.norm();
      const double w = norm <= delta ? 1.0 : delta / norm;
      Eigen::Matrix<double, 2, 3> projection;
      projection << k.fx / c.z(), 0.0, -k.fx * c.x() / (c.z() * c.z()), 0.0, k.fy / c.z(),
        -k.fy * c.y() / (c.z() * c.z());
      Eigen::Matrix<double, 2, 6> jc;
      jc.leftCols<3>() = -projection * skew(rotated); // d c / d theta = -[R X]x
      jc.rightCols<3>() = projection;
      const Eigen::Matrix<double, 2, 3> jp = projection * x.rotation[o.camera];
      U[o.camera] += w * jc.transpose() * jc;
      gc[o.camera] += w * jc.transpose() * r;
      V[o.point] += w * jp.transpose() * jp;
      gp[o.point] += w * jp.transpose() * r;
      W[a] = w * jc.transpose() * jp;
    }

    bool improved = false;
    while (!improved)
    {
      // Schur complement on the free cameras.
      Eigen::MatrixXd S = Eigen::MatrixXd::Zero(dimension, dimension);
      Eigen::VectorXd b = Eigen::VectorXd::Zero(dimension);
      for (int j = 0; j < m; ++j)
      {
        if (block[j] < 0)
        {
          continue;
        }
        Matrix6d damped = U[j];
        damped.diagonal() += lambda * U[j].diagonal() + Vector6d::Constant(1e-12);
        S.block<6, 6>(6 * block[j], 6 * block[j]) = damped;
        b.segment<6>(6 * block[j]) = -gc[j];
      }
      std::vector<Eigen::Matrix3d> Vinv(static_cast<size_t>(n));
      for (int i = 0; i < n; ++i)
      {
        Eigen::Matrix3d damped = V[i];
        damped.diagonal() += lambda * V[i].diagonal() + Eigen::Vector3d::Constant(1e-12);
        Vinv[i] = damped.inverse();
        const std::vector<int>& seen = observationsOf[i];
        for (int a : seen)
        {
          const int ja = block[observations[a].camera];
          if (ja < 0)
          {
            continue;
          }
          const Matrix63d Y = W[a] * Vinv[i];
          b.segment<6>(6 * ja) += Y * gp[i];
          for (int c : seen)
          {
            const int jc = block[observations[c].camera];
            if (jc >= 0)
            {
              S.block<6, 6>(6 * ja, 6 * jc) -= Y * W[c].transpose();
            }
          }
        }
      }
      if (scaleParameter >= 0)
      {
        S.row(scaleParameter).setZero();
        S.col(scaleParameter).setZero();
        S(scaleParameter, scaleParameter) = 1.0;
        b(scaleParameter) = 0.0;
      }
      const Eigen::VectorXd step = dimension > 0 ? Eigen::VectorXd(S.ldlt().solve(b)) : b;

      State trial = x;
      for (int j = 0; j < m; ++j)
      {
        if (block[j] < 0)
        {
          continue;
        }
        const Vector6d d = step.segment<6>(6 * block[j]);
        trial.rotation[j] = rotationFromVector(d.head<3>()) * x.rotation[j];
        trial.translation[j] = x.translation[j] + d.tail<3>();
      }
      for (int i = 0; i < n; ++i)
      {
        Eigen::Vector3d rhs = -gp[i];
        for (int a : observationsOf[i])
        {
          const int ja = block[observations[a].camera];
          if (ja >= 0)
          {
            rhs -= W[a].transpose() * step.segment<6>(6 * ja);
          }
        }
        trial.points[i] = x.points[i] + Vinv[i] * rhs;
      }
      double trialCost = 0.0;
      double trialSquares = 0.0;
      const bool finite = step.allFinite();
      if (finite)
      {
        evaluate(trial, intrinsics, observations, delta, trialCost, trialSquares);
      }
      if (finite && trialCost < cost)
      {
        const double decrease = (cost - trialCost) / std::max(cost, 1e-300);
        x = std::move(trial);
        cost = trialCost;
        squares = trialSquares;
        lambda = std::max(lambda / 3.0, 1e-12);
        improved = true;
        summary.iterations = iteration + 1;
        if (decrease < options.relativeTolerance)
        {
          iteration = options.maxIterations; // converged
        }
      }
      else
      {
        lambda *= 4.0;
        if (lambda > 1e10)
        {
          iteration = options.maxIterations; // no step lowers the cost: at a minimum
          break;
        }
      }
    }
  }

  for (int j = 0; j < m; ++j)
  {
    cameras[j].rotation = nearestRotation(x.rotation[j].transpose());
    cameras[j].centre = -x.rotation[j].transpose() * x.translation[j];
  }
  points = x.points;
  summary.finalRmsPx = observations.empty() ? 0.0 : std::sqrt(squares / observations.size());
  return summary;
}

} // namespace vimlop
