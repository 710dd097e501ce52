#include <vimlop/Core/ContourMatcher.h>

#include <vimlop/Core/Error.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vimlop
{

namespace
{

struct Evaluator
{
  Eigen::Matrix2d information;
  double kappa;
  double minCos;
  double lambdaMax;

  explicit Evaluator(const ContourMatchOptions& o)
    : kappa(o.kappa)
    , minCos(std::cos(o.maxAngleDeg * M_PI / 180.0))
  {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(o.positionCovariancePx2);
    if (!(eig.eigenvalues()[0] > 0.0) || !o.positionCovariancePx2.allFinite())
    {
      throw Error("contour matching: the 2-D position covariance is not positive definite");
    }
    if (!(o.kappa >= 0.0))
    {
      throw Error("contour matching: kappa must not be negative");
    }
    information = o.positionCovariancePx2.inverse();
    lambdaMax = eig.eigenvalues()[1];
  }

  /// Fills `match` if model sample `m` is admissible and better; returns true then.
  bool consider(const ContourPoint& x, const ModelContourPoint& y, int m, ContourMatch& match) const
  {
    const double cosAngle = std::clamp(y.pixelNormal.dot(x.normal), -1.0, 1.0);
    if (cosAngle < minCos)
    {
      return false;
    }
    const Eigen::Vector2d e = y.pixel - x.pixel;
    const double m2 = e.dot(information * e);
    const double cost = 0.5 * m2 + kappa * (1.0 - cosAngle);
    if (cost >= match.cost)
    {
      return false;
    }
    match.model = m;
    match.cost = cost;
    match.mahalanobis2 = m2;
    match.angleRad = std::acos(cosAngle);
    match.errorPx = e;
    return true;
  }
};

ContourMatch unmatched(int video)
{
  ContourMatch match;
  match.video = video;
  match.cost = std::numeric_limits<double>::infinity();
  return match;
}

} // namespace

std::vector<ContourMatch> matchContours(const std::vector<ContourPoint>& video,
  const std::vector<ModelContourPoint>& model, const KdTree2D& modelTree,
  const ContourMatchOptions& options)
{
  const Evaluator evaluator(options);
  std::vector<ContourMatch> matches;
  matches.reserve(video.size());
  for (int i = 0; i < static_cast<int>(video.size()); ++i)
  {
    ContourMatch match = unmatched(i);
    double radius2 = std::numeric_limits<double>::infinity();
    modelTree.visit(video[i].pixel, radius2,
      [&](int m)
      {
        if (evaluator.consider(video[i], model[m], m, match))
        {
          // Orientation cost is >= 0, so cost >= ½|e|²/λmax bounds the distance.
          radius2 = 2.0 * match.cost * evaluator.lambdaMax;
        }
      });
    matches.push_back(match);
  }
  return matches;
}

std::vector<ContourMatch> matchContoursBruteForce(const std::vector<ContourPoint>& video,
  const std::vector<ModelContourPoint>& model, const ContourMatchOptions& options)
{
  const Evaluator evaluator(options);
  std::vector<ContourMatch> matches;
  for (int i = 0; i < static_cast<int>(video.size()); ++i)
  {
    ContourMatch match = unmatched(i);
    for (int m = 0; m < static_cast<int>(model.size()); ++m)
    {
      evaluator.consider(video[i], model[m], m, match);
    }
    matches.push_back(match);
  }
  return matches;
}

} // namespace vimlop
