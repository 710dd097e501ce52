#include <vimlop/Results/RecordJson.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationOptionTable.h>
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

void readValue(const json& j, const char* key, double& field)
{
  field = j.contains(key) && j.at(key).is_null() ? std::numeric_limits<double>::infinity()
                                                 : j.value(key, field);
}

void readValue(const json& j, const char* key, int& field)
{
  field = intValue(j, key, field);
}

void readValue(const json& j, const char* key, bool& field)
{
  field = j.value(key, field);
}

json optionsJson(const RegistrationOptions& o)
{
  json j = { { "method", toString(o.method) },
    { "contour_position_covariance_px2", matrixJson(o.contourMatch.positionCovariancePx2) },
    { "min_scale", o.minScale }, { "max_scale", boundJson(o.maxScale) } };
#define VIMLOP_VALUE_JSON(Name, Type, member, key, flag, min, max, help) j[key] = o.member;
#define VIMLOP_SWITCH_JSON(Name, member, key, flag, help) j[key] = o.member;
  VIMLOP_REGISTRATION_VALUES(VIMLOP_VALUE_JSON)
  VIMLOP_REGISTRATION_SWITCHES(VIMLOP_SWITCH_JSON)
#undef VIMLOP_VALUE_JSON
#undef VIMLOP_SWITCH_JSON
  return j;
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
  o.minScale = j.value("min_scale", o.minScale);
  readValue(j, "max_scale", o.maxScale);
#define VIMLOP_VALUE_FROM(Name, Type, member, key, flag, min, max, help)                           \
  readValue(j, key, o.member);
#define VIMLOP_SWITCH_FROM(Name, member, key, flag, help) readValue(j, key, o.member);
  VIMLOP_REGISTRATION_VALUES(VIMLOP_VALUE_FROM)
  VIMLOP_REGISTRATION_SWITCHES(VIMLOP_SWITCH_FROM)
#undef VIMLOP_VALUE_FROM
#undef VIMLOP_SWITCH_FROM
  return o;
}

json versionsJson(const RegistrationRecord& record)
{
  json versions = { { "vimlop", VIMLOP_VERSION } };
  for (const auto& [name, version] : record.versions)
  {
    versions[name] = version;
  }
  return versions;
}

json inputsJson(const RegistrationRecord& record)
{
  json inputs = json::array();
  for (const RegistrationRecord::InputFile& input : record.inputs)
  {
    inputs.push_back({ { "role", input.role }, { "path", input.path }, { "bytes", input.bytes },
      { "sha256", input.sha256 } });
  }
  return inputs;
}

} // namespace vimlop::recordjson
