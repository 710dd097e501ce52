#include <vimlop/Core/RegistrationOptions.h>

#include <vimlop/Core/Error.h>

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

void RegistrationOptions::validate() const
{
  std::ostringstream problem;
  if (!(this->minScale >= 0.0) || std::isnan(this->maxScale) ||
    !(this->minScale <= this->maxScale) || !(this->maxScale > 0.0))
  {
    problem << "scale bounds are invalid: min " << this->minScale << " > max " << this->maxScale
            << " or negative";
  }
  else if (!(this->trimFraction >= 0.0 && this->trimFraction < 1.0))
  {
    problem << "trim fraction must lie in [0, 1), got " << this->trimFraction;
  }
  else if (!(this->chiSquareProbability > 0.0 && this->chiSquareProbability < 1.0))
  {
    problem << "chi-square probability must lie in (0, 1), got " << this->chiSquareProbability;
  }
  else if (!(this->maxContourOutlierFraction >= 0.0 && this->maxContourOutlierFraction <= 1.0))
  {
    problem << "contour outlier fraction must lie in [0, 1], got "
            << this->maxContourOutlierFraction;
  }
  else if (!(this->contourSampleSpacingPx > 0.0))
  {
    problem << "contour sample spacing must be positive, got " << this->contourSampleSpacingPx;
  }
  else if (!(this->contourMatch.kappa >= 0.0) || !(this->contourMatch.maxAngleRad > 0.0))
  {
    problem << "kappa must be non-negative and the normal angle bound positive";
  }
  else if (this->maxIterations < 1 || this->maxBackoffSteps < 0 || this->stallIterations < 1)
  {
    problem << "iteration cap must be at least 1 and back-off steps non-negative";
  }
  else if (!(this->convergenceTranslationMm >= 0.0 && this->convergenceRotationDeg >= 0.0 &&
             this->convergenceScaleRelative >= 0.0))
  {
    problem << "convergence thresholds must be non-negative";
  }
  if (!problem.str().empty())
  {
    throw Error("registration options: " + problem.str());
  }
}

} // namespace vimlop
