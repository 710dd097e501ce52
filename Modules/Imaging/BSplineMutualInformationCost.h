#ifndef vimlop_BSplineMutualInformationCost_h
#define vimlop_BSplineMutualInformationCost_h

// Private to the Imaging module (not installed); see TemplateRegistrationITK.h.
// Exported for its tests only.

#include "VIMLOPImagingModule.h"
#include <vimlop/Core/TaskPool.h>
#include <vimlop/Imaging/TemplateRegistrationITK.h>

#include <itkImageBase.h>
#include <vnl/vnl_cost_function.h>

#include <cstddef>
#include <vector>

namespace vimlop::templatereg
{

/// Control points that support a point of a cubic B-spline in 3-D.
constexpr int kBSplineSupport = 64;

/// @brief The control grid of a cubic B-spline: its coefficient image's size and spacing.
struct BSplineGrid
{
  long size[3] = { 0, 0, 0 };
  double spacingMm[3] = { 1.0, 1.0, 1.0 };
  /// Control points per displacement component.
  long nodes() const { return size[0] * size[1] * size[2]; }
};

/// @brief A fixed-image sample with the B-spline weights of its 64 control
/// points: they depend on the point only, so they are computed once per level.
struct BSplineSample
{
  double xMm[3];
  double fixedValue;
  /// Linear index, in the control grid, of the support's first node.
  long firstNode;
  float weights[kBSplineSupport];
};

/**
 * @brief `count` samples at uniformly random positions of `fixed` (not at
 * its voxel centres: mutual information sampled on the grid of one image and
 * interpolated in the other favours grid-aligned positions), with their
 * weights on the control grid `grid` (a B-spline's coefficient image).
 * Positions whose support leaves the grid are dropped (the B-spline is the
 * identity there). Deterministic for a `seed`.
 */
VIMLOPIMAGING_EXPORT std::vector<BSplineSample> drawBSplineSamples(
  const Image* fixed, const itk::ImageBase<3>* grid, std::size_t count, unsigned seed);

/**
 * @brief The cost of the B-spline stage over its control-point coefficients
 * c (ITK's layout: all x components, then y, then z; mm): the negated Mattes
 * mutual information of the fixed samples and `moving` under x -> affine(x +
 * sum_k w_k(x) c_k), plus `bendingWeightMm2` times the bending energy of the
 * displacement. Its derivative is exact and sparse: each sample adds to the
 * 3 x 64 coefficients of its support only. (ITK's v4 metrics fill the
 * B-spline's Jacobian as a dense 3 x (all coefficients) matrix at each
 * sample, which made the stage three times slower than elastix.)
 *
 * Mutual information: fixed intensities fall into bins (a box window),
 * moving ones into a cubic Parzen window, two bins of padding at each end
 * (Mattes et al. 2003); d MI = sum_ij dp_ij log(p_ij / p_j).
 */
class VIMLOPIMAGING_EXPORT BSplineMutualInformationCost : public vnl_cost_function
{
public:
  /// `affine` maps the B-spline's output to `moving` (rows of [A | t], mm).
  BSplineMutualInformationCost(std::vector<BSplineSample> samples, const Image* moving,
    const double affine[3][4], const BSplineGrid& grid, int bins, double bendingWeightMm2);

  /// @brief The cost at `c`, and its gradient when `gradient` is given.
  void compute(const vnl_vector<double>& c, double* value, vnl_vector<double>* gradient) override;

  /**
   * @brief Mean, over the inner control points, of the squared Frobenius
   * norm of the displacement's Hessian (1/mm^2), from second differences of
   * the coefficients: a thin plate's bending energy. Adds its derivative
   * times `weight` to `gradient` when given.
   */
  double bendingEnergy(
    const vnl_vector<double>& c, double weight, vnl_vector<double>* gradient) const;

  /// @brief Samples the cost uses.
  std::size_t sampleCount() const { return samples_.size(); }

private:
  template <class F>
  void forEachNode(const BSplineSample& sample, F&& f) const;
  template <class F>
  void parallel(F&& f);

  /// Chunks of the samples, each with its own histogram and gradient.
  static constexpr long kChunks = 16;

  std::vector<BSplineSample> samples_;
  const Image* moving_;
  double affine_[3][4];
  BSplineGrid grid_;
  int bins_;
  double bendingWeightMm2_;
  TaskPool pool_;
  double fixedMin_ = 0.0;
  double fixedBin_ = 1.0;
  double movingMin_ = 0.0;
  double movingBin_ = 1.0;
  // Per sample, from the last pass over them: fixed bin (-1: outside the
  // moving image), moving histogram position, derivative of the moving
  // intensity in the B-spline's output.
  std::vector<int> sampleBin_;
  std::vector<double> movingPosition_;
  std::vector<double> movingGradient_;
};

} // namespace vimlop::templatereg

#endif
