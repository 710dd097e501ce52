#ifndef vimlop_NoiseModel_h
#define vimlop_NoiseModel_h

#include <Eigen/Core>

#include <string>

/**
 * @file NoiseModel.h
 * @brief 3-D positional noise models of SfM points (V1).
 *
 * A point covariance is in mm^2, expressed in the SfM frame's axes: the
 * registration rotates it with the data (R Sigma R^T) but does not scale it,
 * as in the paper, so it describes the noise of the point once registered.
 */

namespace vimlop
{

/// @brief Which 3-D noise model a data set uses (for reports and the CLI).
enum class PointNoiseModel
{
  Isotropic,   ///< sigma^2 I for every point
  ViewAligned, ///< separate std along and across the mean viewing ray
  PerPoint     ///< a covariance per point, e.g. from bundle adjustment
};

/// @brief sigma^2 I, sigma in mm.
Eigen::Matrix3d isotropicCovariance(double sigmaMm);

/**
 * @brief Covariance with std `sigmaAlongMm` along `viewDirection` (any
 * non-zero vector, SfM frame) and `sigmaAcrossMm` in the plane across it.
 * @throws vimlop::Error for a zero or non-finite direction or negative sigmas.
 */
Eigen::Matrix3d viewAlignedCovariance(
  const Eigen::Vector3d& viewDirection, double sigmaAlongMm, double sigmaAcrossMm);

/**
 * @brief Checks that `covariance` is finite, symmetric and positive definite.
 * @return an empty string if it is, else what is wrong (for error messages).
 */
std::string covarianceProblem(const Eigen::Matrix3d& covariance);

/// @brief Name of a noise model, as used on the command line ("isotropic", ...).
const char* toString(PointNoiseModel model);

} // namespace vimlop

#endif
