#ifndef vimlop_ChiSquare_h
#define vimlop_ChiSquare_h

namespace vimlop
{

/**
 * @brief Cumulative distribution function of the chi-square distribution with
 * `degreesOfFreedom` (> 0) at `x` (>= 0), via the regularised lower
 * incomplete gamma function.
 */
double chiSquareCdf(double x, int degreesOfFreedom);

/**
 * @brief Inverse CDF (quantile) of the chi-square distribution: the `x` with
 * chiSquareCdf(x, k) == p, for p in (0, 1). MATLAB's chi2inv(p, k).
 * @throws vimlop::Error if p is outside (0, 1) or k < 1.
 */
double chiSquareQuantile(double p, int degreesOfFreedom);

} // namespace vimlop

#endif
