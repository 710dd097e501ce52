#include <vimlop/Core/ChiSquare.h>

#include <vimlop/Core/Error.h>

#include <cmath>
#include <limits>
#include <string>

namespace vimlop
{

namespace
{

/// log Gamma(k / 2) by the recurrence Gamma(a + 1) = a Gamma(a) from
/// Gamma(1) = 1 and Gamma(1/2) = sqrt(pi). std::lgamma would do, but glibc's
/// writes the global `signgam`, a data race when registrations run in
/// parallel threads; half-integers are all a chi-square CDF needs.
double logGammaOfHalf(int k)
{
  double a = (k % 2 == 0) ? 1.0 : 0.5;
  double logGamma = (k % 2 == 0) ? 0.0 : 0.5 * std::log(3.14159265358979323846);
  for (; 2.0 * a < k; a += 1.0)
  {
    logGamma += std::log(a);
  }
  return logGamma;
}

/// Regularised lower incomplete gamma P(a, x) with a = k / 2: series for
/// x < a + 1, continued fraction (modified Lentz) otherwise; both to double
/// precision.
double regularizedGammaP(int k, double x)
{
  if (x <= 0.0)
  {
    return 0.0;
  }
  const double a = 0.5 * k;
  const double logPrefactor = a * std::log(x) - x - logGammaOfHalf(k);
  if (x < a + 1.0)
  {
    double term = 1.0 / a;
    double sum = term;
    for (int n = 1; n < 1000; ++n)
    {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-16)
      {
        break;
      }
    }
    return sum * std::exp(logPrefactor);
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / tiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 1000; ++i)
  {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < tiny ? tiny : d;
    c = b + an / c;
    c = std::abs(c) < tiny ? tiny : c;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16)
    {
      break;
    }
  }
  return 1.0 - std::exp(logPrefactor) * h;
}

} // namespace

double chiSquareCdf(double x, int degreesOfFreedom)
{
  return regularizedGammaP(degreesOfFreedom, 0.5 * x);
}

double chiSquareQuantile(double p, int degreesOfFreedom)
{
  if (!(p > 0.0 && p < 1.0))
  {
    throw Error("chi-square probability must lie in (0, 1), got " + std::to_string(p));
  }
  if (degreesOfFreedom < 1)
  {
    throw Error("chi-square degrees of freedom must be at least 1");
  }
  // Bracket, then bisect: the CDF is monotone and evaluating it is cheap.
  double lo = 0.0;
  double hi = std::max(1.0, static_cast<double>(degreesOfFreedom));
  while (chiSquareCdf(hi, degreesOfFreedom) < p)
  {
    lo = hi;
    hi *= 2.0;
  }
  for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (chiSquareCdf(mid, degreesOfFreedom) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

} // namespace vimlop
