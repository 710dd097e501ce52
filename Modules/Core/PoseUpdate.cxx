#include <vimlop/Core/PoseUpdate.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TaskPool.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace vimlop
{

namespace
{

using Matrix37 = Eigen::Matrix<double, 3, 7>;
using Matrix47 = Eigen::Matrix<double, 4, 7>;
using Matrix7 = Eigen::Matrix<double, 7, 7>;

/// Pairs per task when summing in parallel; fixed so sums never depend on threads.
constexpr int Chunk = 128;
/// Camera depth below which a projected point is clamped (mm): keeps the
/// projection finite if a trial step puts a point behind the camera.
constexpr double MinDepthMm = 1e-3;

/// w = Rᵀ (y - t) - s x and its derivative with respect to the left increment.
inline Eigen::Vector3d moved(
  const SimilarityTransform& T, const Eigen::Vector3d& x, const Eigen::Vector3d& y, Matrix37* dw)
{
  const Eigen::Matrix3d Rt = T.rotation.transpose();
  if (dw)
  {
    dw->col(0) = -(Rt * T.apply(x));
    dw->block<3, 3>(0, 1) = Rt * skew(y);
    dw->block<3, 3>(0, 4) = -Rt;
  }
  return Rt * (y - T.translation) - T.scale * x;
}

inline void pointBlock(
  const PointPair& p, const SimilarityTransform& T, Eigen::Vector3d& r, Matrix37* J)
{
  Matrix37 dw;
  r = p.whitening * moved(T, p.data, p.model, J ? &dw : nullptr);
  if (J)
  {
    *J = p.whitening * dw;
  }
}

inline void contourBlock(const PoseUpdateProblem& problem, const ContourPair& c,
  const SimilarityTransform& T, Eigen::Vector4d& r, Matrix47* J)
{
  const VideoFrame& frame = (*problem.frames)[static_cast<size_t>(c.frame)];
  const PinholeCamera& k = frame.intrinsics;
  const Eigen::Matrix3d Rct = frame.cameraToSfm.rotation.transpose();
  Matrix37 du;
  const Eigen::Vector3d p =
    Rct * moved(T, frame.cameraToSfm.centre, c.modelPoint, J ? &du : nullptr);
  const double z = std::max(p.z(), MinDepthMm);
  const Eigen::Vector2d pixel(k.fx * p.x() / z + k.cx, k.fy * p.y() / z + k.cy);
  r.head<2>() = problem.contourWhitening * (pixel - c.videoPixel);

  const double sqrtKappa = std::sqrt(problem.kappa);
  const Eigen::Matrix3d toCamera = Rct * T.rotation.transpose();
  const Eigen::Vector3d n = toCamera * c.modelNormal;
  const Eigen::Vector2d v(k.fx * n.x(), k.fy * n.y());
  const double vn = v.norm();
  const bool oriented = vn > 1e-9;
  const Eigen::Vector2d nh = oriented ? Eigen::Vector2d(v / vn) : c.videoNormal;
  r.tail<2>() = sqrtKappa * (nh - c.videoNormal);
  if (!J)
  {
    return;
  }
  Eigen::Matrix<double, 2, 3> dproj;
  dproj << k.fx / z, 0.0, -k.fx * p.x() / (z * z), 0.0, k.fy / z, -k.fy * p.y() / (z * z);
  J->topRows<2>() = problem.contourWhitening * dproj * Rct * du;
  J->bottomRows<2>().setZero();
  if (oriented)
  {
    Eigen::Matrix<double, 2, 3> dv;
    dv << k.fx, 0.0, 0.0, 0.0, k.fy, 0.0;
    const Eigen::Matrix2d dnh = (Eigen::Matrix2d::Identity() - nh * nh.transpose()) / vn;
    J->block<2, 3>(2, 1) = sqrtKappa * dnh * dv * toCamera * skew(c.modelNormal);
  }
}

struct Normal
{
  Matrix7 H = Matrix7::Zero();
  Eigen::Matrix<double, 7, 1> g = Eigen::Matrix<double, 7, 1>::Zero();
  double cost = 0.0;
};

void checkProblem(const PoseUpdateProblem& problem)
{
  if (!problem.contours.empty() && !problem.frames)
  {
    throw Error("pose update: contour pairs without frames");
  }
}

/// Cost and, if wanted, normal equations; summed per fixed chunk, then in order.
Normal accumulate(
  const PoseUpdateProblem& problem, const SimilarityTransform& T, bool withJacobian, TaskPool* pool)
{
  const int np = static_cast<int>(problem.points.size());
  const int nc = static_cast<int>(problem.contours.size());
  const int chunksPoints = (np + Chunk - 1) / Chunk;
  const int chunks = chunksPoints + (nc + Chunk - 1) / Chunk;
  std::vector<Normal> partial(static_cast<size_t>(chunks));
  auto task = [&](int t)
  {
    Normal& out = partial[static_cast<size_t>(t)];
    if (t < chunksPoints)
    {
      Eigen::Vector3d r;
      Matrix37 J;
      for (int i = t * Chunk; i < std::min(np, (t + 1) * Chunk); ++i)
      {
        pointBlock(problem.points[i], T, r, withJacobian ? &J : nullptr);
        out.cost += 0.5 * r.squaredNorm();
        if (withJacobian)
        {
          out.H.noalias() += J.transpose() * J;
          out.g.noalias() += J.transpose() * r;
        }
      }
      return;
    }
    Eigen::Vector4d r;
    Matrix47 J;
    const int c0 = (t - chunksPoints) * Chunk;
    for (int i = c0; i < std::min(nc, c0 + Chunk); ++i)
    {
      contourBlock(problem, problem.contours[i], T, r, withJacobian ? &J : nullptr);
      out.cost += 0.5 * r.squaredNorm();
      if (withJacobian)
      {
        out.H.noalias() += J.transpose() * J;
        out.g.noalias() += J.transpose() * r;
      }
    }
  };
  if (pool)
  {
    pool->run(chunks, task);
  }
  else
  {
    for (int t = 0; t < chunks; ++t)
    {
      task(t);
    }
  }
  Normal total;
  for (const Normal& p : partial)
  {
    total.H += p.H;
    total.g += p.g;
    total.cost += p.cost;
  }
  return total;
}

} // namespace

double poseUpdateCost(
  const PoseUpdateProblem& problem, const SimilarityTransform& T, TaskPool* pool)
{
  checkProblem(problem);
  return accumulate(problem, T, false, pool).cost;
}

void poseUpdateResiduals(const PoseUpdateProblem& problem, const SimilarityTransform& T,
  Eigen::VectorXd& residuals, Eigen::MatrixXd& jacobian)
{
  checkProblem(problem);
  const int np = static_cast<int>(problem.points.size());
  const int nc = static_cast<int>(problem.contours.size());
  residuals.resize(3 * np + 4 * nc);
  jacobian.resize(3 * np + 4 * nc, 7);
  for (int i = 0; i < np; ++i)
  {
    Eigen::Vector3d r;
    Matrix37 J;
    pointBlock(problem.points[i], T, r, &J);
    residuals.segment<3>(3 * i) = r;
    jacobian.block<3, 7>(3 * i, 0) = J;
  }
  for (int i = 0; i < nc; ++i)
  {
    Eigen::Vector4d r;
    Matrix47 J;
    contourBlock(problem, problem.contours[i], T, r, &J);
    residuals.segment<4>(3 * np + 4 * i) = r;
    jacobian.block<4, 7>(3 * np + 4 * i, 0) = J;
  }
}

PoseUpdateResult solvePoseUpdate(const PoseUpdateProblem& problem,
  const SimilarityTransform& initial, const PoseUpdateOptions& options, TaskPool* pool)
{
  checkProblem(problem);
  if (!(problem.minScale <= problem.maxScale) || !(problem.minScale >= 0.0))
  {
    throw Error("pose update: the scale bounds are invalid (need 0 <= min <= max)");
  }
  PoseUpdateResult result;
  result.transform = initial;
  result.transform.scale =
    std::clamp(initial.scale, std::max(problem.minScale, 1e-300), problem.maxScale);
  Normal normal = accumulate(problem, result.transform, true, pool);
  result.initialCost = normal.cost;
  result.finalCost = normal.cost;
  double lambda = 1e-4;
  for (int iteration = 0; iteration < options.maxIterations; ++iteration)
  {
    bool accepted = false;
    while (!accepted && lambda < 1e12)
    {
      // Marquardt damping on the diagonal, with a floor for flat directions.
      Matrix7 A = normal.H;
      const double floor = 1e-12 * std::max(1.0, normal.H.diagonal().maxCoeff());
      for (int i = 0; i < 7; ++i)
      {
        A(i, i) += lambda * std::max(normal.H(i, i), floor);
      }
      Eigen::Matrix<double, 7, 1> delta = A.ldlt().solve(-normal.g);
      // V7: keep s e^δσ inside the bounds; if the step leaves them, pin δσ at
      // the bound and solve for the other six parameters.
      const double s = result.transform.scale;
      const double lo = std::log(std::max(problem.minScale, 1e-300) / s);
      const double hi = std::log(problem.maxScale / s);
      bool pinned = false;
      if (delta[0] < lo || delta[0] > hi)
      {
        const double ds = std::clamp(delta[0], lo, hi);
        const Eigen::Matrix<double, 6, 6> A6 = A.bottomRightCorner<6, 6>();
        const Eigen::Matrix<double, 6, 1> b6 = -(normal.g.tail<6>() + A.block<6, 1>(1, 0) * ds);
        delta[0] = ds;
        delta.tail<6>() = A6.ldlt().solve(b6);
        pinned = true;
      }
      if (!delta.allFinite())
      {
        lambda *= 10.0;
        continue;
      }
      SimilarityTransform trial = SimilarityTransform::exp(delta).compose(result.transform);
      if (pinned)
      {
        trial.scale = std::clamp(trial.scale, std::max(problem.minScale, 1e-300), problem.maxScale);
      }
      const double trialCost = accumulate(problem, trial, false, pool).cost;
      if (trialCost < result.finalCost)
      {
        const double decrease = result.finalCost - trialCost;
        result.transform = trial;
        result.finalCost = trialCost;
        result.scaleAtBound = pinned;
        result.iterations = iteration + 1;
        lambda = std::max(lambda / 10.0, 1e-12);
        accepted = true;
        if (decrease <= options.relativeTolerance * trialCost)
        {
          return result;
        }
        normal = accumulate(problem, result.transform, true, pool);
      }
      else
      {
        lambda *= 10.0;
      }
    }
    if (!accepted)
    {
      break; // no step decreases the cost: at a minimum within round-off
    }
  }
  return result;
}

} // namespace vimlop
