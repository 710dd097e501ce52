#ifndef vimlop_TemplateRegistrationITK_h
#define vimlop_TemplateRegistrationITK_h

// Private to the translation units of TemplateRegistration (not installed):
// the driver (TemplateRegistration.cxx, which defines what is declared here),
// the affine, B-spline and SyN stages. Each stage instantiates ITK's heavy v4
// registration templates in a unit of its own, so that a change to one does
// not rebuild the other. Like every ITK translation unit they include no
// Eigen (see CTVolume.h).

#include <vimlop/Imaging/CTVolume.h>

#include <itkAffineTransform.h>
#include <itkDisplacementFieldTransform.h>
#include <itkFixedArray.h>
#include <itkImage.h>
#include <itkMacro.h>

#include <array>
#include <functional>
#include <string>

namespace vimlop::templatereg
{

using Image = itk::Image<float, 3>;
using AffineTransform = itk::AffineTransform<double, 3>;
using FieldTransform = itk::DisplacementFieldTransform<double, 3>;
/// A stage's map composed before the next stage (template to patient).
using InitialTransform = itk::Transform<double, 3, 3>;
using Point = itk::Point<double, 3>;
/// A point map, template to patient or back (mm).
using PointMap = std::function<Point(const Point&)>;

/// @brief `p` (mm) as an ITK point.
Point toPoint(const std::array<double, 3>& p);

/// @brief Integer shrink factors per axis that bring `spacingMm` closest to `targetMm`.
itk::FixedArray<unsigned, 3> shrinkFactors(const std::array<double, 3>& spacingMm, double targetMm);

/// @brief Fraction of the fixed crop's voxels (every other one) that `map` sends into `patient`.
double overlap(const CTVolume& fixed, const CTVolume& patient, const PointMap& map);

/// @brief Pearson correlation between the fixed crop and the patient at mapped points (stride 2).
double correlation(const CTVolume& fixed, const Image* patient, const PointMap& map);

/// @brief Throws the error of a template crop of which only `fraction` maps into the patient CT.
[[noreturn]] void noOverlap(double fraction);

/**
 * @brief Rethrows an ITK failure of `stage` as a one-line vimlop::Error.
 * "Samples map outside" means the transform has left the moving image: the
 * images do not overlap, and `overlapNow` says by how much.
 */
[[noreturn]] void registrationFailed(const itk::ExceptionObject& e, const std::string& stage,
  const std::function<double()>& overlapNow);

} // namespace vimlop::templatereg

#endif
