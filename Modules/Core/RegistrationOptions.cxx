#include <vimlop/Core/RegistrationOptions.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/OptionRange.h>
#include <vimlop/Core/RegistrationOptionTable.h>

#include <Eigen/LU>

#include <cmath>
#include <sstream>

namespace vimlop
{

const char* toString(RegistrationMethod method)
{
  switch (method)
  {
    case RegistrationMethod::VIMLOP:
      return "vimlop";
    case RegistrationMethod::IMLP:
      return "imlp";
    case RegistrationMethod::TrimmedICP:
      return "trimmed-icp";
  }
  return "unknown";
}

RegistrationMethod registrationMethodFromString(const std::string& name)
{
  for (RegistrationMethod method :
    { RegistrationMethod::VIMLOP, RegistrationMethod::IMLP, RegistrationMethod::TrimmedICP })
  {
    if (name == toString(method))
    {
      return method;
    }
  }
  throw Error("unknown registration method '" + name + "' (expected vimlop, imlp or trimmed-icp)");
}

void RegistrationOptions::validate() const
{
  const std::string context = "registration options";
  if (!(this->minScale >= 0.0) || std::isnan(this->maxScale) ||
    !(this->minScale <= this->maxScale) || !(this->maxScale > 0.0))
  {
    std::ostringstream problem;
    problem << context << ": scale bounds are invalid: min " << this->minScale << " > max "
            << this->maxScale << " or negative";
    throw Error(problem.str());
  }
  const Eigen::Matrix2d& covariance = this->contourMatch.positionCovariancePx2;
  if (!covariance.allFinite() || covariance(0, 1) != covariance(1, 0) ||
    !(covariance(0, 0) > 0.0) || !(covariance.determinant() > 0.0))
  {
    throw Error(context + ": the contour position covariance must be symmetric positive definite");
  }
#define VIMLOP_CHECK_VALUE(Name, Type, member, key, flag, min, max, help)                          \
  requireInRange(context, key, this->member, min, max);
  VIMLOP_REGISTRATION_VALUES(VIMLOP_CHECK_VALUE)
#undef VIMLOP_CHECK_VALUE
}

} // namespace vimlop
