#include <vimlop/Results/RecordJson.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Results/RegistrationRecordIO.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace vimlop::recordjson
{

namespace
{

/// Infinite bounds are written as null (JSON has no infinity).
json boundJson(double value)
{
  return std::isfinite(value) ? json(value) : json(nullptr);
}

double boundFrom(const json& j, const char* key, double infinity)
{
  if (!j.contains(key) || j.at(key).is_null())
  {
    return infinity;
  }
  return j.at(key).get<double>();
}

} // namespace

int intValue(const json& j, const char* key, int fallback)
{
  if (!j.is_object() || !j.contains(key))
  {
    return fallback;
  }
  const json& v = j.at(key);
  const double x = v.is_number() ? v.get<double>() : 0.5;
  if (x != std::floor(x) || x < std::numeric_limits<int>::min() ||
    x > std::numeric_limits<int>::max())
  {
    throw Error(std::string("\"") + key + "\" is not a whole number in range");
  }
  return static_cast<int>(x);
}

json matrixJson(const Eigen::MatrixXd& m)
{
  json rows = json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
  {
    json row = json::array();
    for (Eigen::Index j = 0; j < m.cols(); ++j)
    {
      row.push_back(m(i, j));
    }
    rows.push_back(row);
  }
  return rows;
}

Eigen::MatrixXd matrixFrom(const json& rows, int n, const std::string& what)
{
  if (!rows.is_array() || static_cast<int>(rows.size()) != n)
  {
    throw Error(what + ": expected a " + std::to_string(n) + " x " + std::to_string(n) + " matrix");
  }
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
  {
    if (!rows[i].is_array() || static_cast<int>(rows[i].size()) != n)
    {
      throw Error(
        what + ": expected a " + std::to_string(n) + " x " + std::to_string(n) + " matrix");
    }
    for (int j = 0; j < n; ++j)
    {
      m(i, j) = rows[i][j].get<double>();
    }
  }
  return m;
}

json transformJson(const SimilarityTransform& t)
{
  return { { "matrix", matrixJson(t.matrix()) }, { "scale", t.scale },
    { "rotation", matrixJson(t.rotation) },
    { "translation", { t.translation.x(), t.translation.y(), t.translation.z() } },
    { "rotation_angle_deg", Eigen::AngleAxisd(t.rotation).angle() * 180.0 / M_PI } };
}

SimilarityTransform transformFrom(const json& j, const std::string& what)
{
  return SimilarityTransform::fromMatrix(
    Eigen::Matrix4d(matrixFrom(j.at("matrix"), 4, what)), 1e-6);
}

json optionsJson(const RegistrationOptions& o)
{
  return { { "method", toString(o.method) },
    { "contour_position_covariance_px2", matrixJson(o.contourMatch.positionCovariancePx2) },
    { "contour_kappa", o.contourMatch.kappa },
    { "max_contour_normal_angle_deg", o.contourMatch.maxAngleRad * 180.0 / M_PI },
    { "contour_sample_spacing_px", o.contourSampleSpacingPx }, { "min_scale", o.minScale },
    { "max_scale", boundJson(o.maxScale) }, { "trim_fraction", o.trimFraction },
    { "chi_square_probability", o.chiSquareProbability },
    { "max_contour_outlier_fraction", o.maxContourOutlierFraction },
    { "equal_influence", o.equalInfluence }, { "anatomical_constraint", o.anatomicalConstraint },
    { "max_backoff_steps", o.maxBackoffSteps }, { "max_iterations", o.maxIterations },
    { "convergence_translation_mm", o.convergenceTranslationMm },
    { "convergence_rotation_deg", o.convergenceRotationDeg },
    { "convergence_scale_relative", o.convergenceScaleRelative }, { "accelerate", o.accelerate },
    { "max_acceleration", o.maxAcceleration },
    { "stall_relative_decrease", o.stallRelativeDecrease },
    { "stall_iterations", o.stallIterations }, { "points_first", o.pointsFirst },
    { "pose_update_max_iterations", o.poseUpdate.maxIterations },
    { "pose_update_relative_tolerance", o.poseUpdate.relativeTolerance },
    { "threads", o.threads } };
}

RegistrationOptions optionsFrom(const json& j)
{
  RegistrationOptions o;
  o.method = registrationMethodFromString(j.value("method", std::string(toString(o.method))));
  if (j.contains("contour_position_covariance_px2"))
  {
    o.contourMatch.positionCovariancePx2 =
      matrixFrom(j.at("contour_position_covariance_px2"), 2, "contour_position_covariance_px2");
  }
  o.contourMatch.kappa = j.value("contour_kappa", o.contourMatch.kappa);
  o.contourMatch.maxAngleRad =
    j.value("max_contour_normal_angle_deg", o.contourMatch.maxAngleRad * 180.0 / M_PI) * M_PI /
    180.0;
  o.contourSampleSpacingPx = j.value("contour_sample_spacing_px", o.contourSampleSpacingPx);
  o.minScale = j.value("min_scale", o.minScale);
  o.maxScale = boundFrom(j, "max_scale", std::numeric_limits<double>::infinity());
  o.trimFraction = j.value("trim_fraction", o.trimFraction);
  o.chiSquareProbability = j.value("chi_square_probability", o.chiSquareProbability);
  o.maxContourOutlierFraction =
    j.value("max_contour_outlier_fraction", o.maxContourOutlierFraction);
  o.equalInfluence = j.value("equal_influence", o.equalInfluence);
  o.anatomicalConstraint = j.value("anatomical_constraint", o.anatomicalConstraint);
  o.maxBackoffSteps = intValue(j, "max_backoff_steps", o.maxBackoffSteps);
  o.maxIterations = intValue(j, "max_iterations", o.maxIterations);
  o.convergenceTranslationMm = j.value("convergence_translation_mm", o.convergenceTranslationMm);
  o.convergenceRotationDeg = j.value("convergence_rotation_deg", o.convergenceRotationDeg);
  o.convergenceScaleRelative = j.value("convergence_scale_relative", o.convergenceScaleRelative);
  o.accelerate = j.value("accelerate", o.accelerate);
  o.maxAcceleration = j.value("max_acceleration", o.maxAcceleration);
  o.stallRelativeDecrease = j.value("stall_relative_decrease", o.stallRelativeDecrease);
  o.stallIterations = intValue(j, "stall_iterations", o.stallIterations);
  o.pointsFirst = j.value("points_first", o.pointsFirst);
  o.poseUpdate.maxIterations =
    intValue(j, "pose_update_max_iterations", o.poseUpdate.maxIterations);
  o.poseUpdate.relativeTolerance =
    j.value("pose_update_relative_tolerance", o.poseUpdate.relativeTolerance);
  o.threads = intValue(j, "threads", o.threads);
  return o;
}

} // namespace vimlop::recordjson
