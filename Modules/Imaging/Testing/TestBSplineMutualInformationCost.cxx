// The cost of the template registration's B-spline stage, on small images
// made in memory: a smooth pattern and the same pattern shifted.
#include <vimlop/Imaging/BSplineMutualInformationCost.h>

#include <gtest/gtest.h>

#include <itkBSplineTransform.h>

#include <cmath>
#include <string>

using namespace vimlop::templatereg;

namespace
{

using BSpline = itk::BSplineTransform<double, 3, 3>;

/// A smooth pattern of three Gaussian blobs (HU-like values), at a point (mm).
double pattern(double x, double y, double z)
{
  auto blob = [&](double cx, double cy, double cz, double r, double v)
  {
    const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz);
    return v * std::exp(-d2 / (2.0 * r * r));
  };
  return -200.0 + blob(8, 9, 10, 3.5, 900.0) + blob(15, 13, 9, 2.5, -600.0) +
    blob(11, 16, 15, 4.0, 500.0);
}

/// A 24^3 image at 1 mm of the pattern moved by `shiftMm`: voxel x holds pattern(x - shift).
Image::Pointer patternImage(const double shiftMm[3])
{
  auto image = Image::New();
  Image::SizeType size;
  size.Fill(24);
  image->SetRegions(size);
  image->Allocate();
  for (unsigned k = 0; k < 24; ++k)
  {
    for (unsigned j = 0; j < 24; ++j)
    {
      for (unsigned i = 0; i < 24; ++i)
      {
        image->SetPixel({ { i, j, k } },
          static_cast<float>(pattern(i - shiftMm[0], j - shiftMm[1], k - shiftMm[2])));
      }
    }
  }
  return image;
}

/// A cubic B-spline over the image's extent, `cells` mesh cells a side.
BSpline::Pointer bsplineOver(const Image* image, unsigned cells)
{
  auto bspline = BSpline::New();
  BSpline::PhysicalDimensionsType dimensions;
  dimensions.Fill(23.0);
  BSpline::MeshSizeType mesh;
  mesh.Fill(cells);
  bspline->SetTransformDomainOrigin(image->GetOrigin());
  bspline->SetTransformDomainDirection(image->GetDirection());
  bspline->SetTransformDomainPhysicalDimensions(dimensions);
  bspline->SetTransformDomainMeshSize(mesh);
  return bspline;
}

BSplineGrid gridOf(const BSpline* bspline)
{
  BSplineGrid grid;
  const auto* coefficients = bspline->GetCoefficientImages()[0].GetPointer();
  for (unsigned a = 0; a < 3; ++a)
  {
    grid.size[a] = static_cast<long>(coefficients->GetLargestPossibleRegion().GetSize()[a]);
    grid.spacingMm[a] = coefficients->GetSpacing()[a];
  }
  return grid;
}

constexpr double kIdentity[3][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } };
constexpr double kShiftMm[3] = { 1.2, -0.7, 0.5 };
constexpr double kNoShiftMm[3] = { 0.0, 0.0, 0.0 };

/// Fixed: the pattern; moving: the pattern moved by kShiftMm; a 3-cell grid.
struct ShiftedPattern
{
  Image::Pointer fixed = patternImage(kNoShiftMm);
  Image::Pointer moving = patternImage(kShiftMm);
  BSpline::Pointer bspline = bsplineOver(fixed, 3);
  BSplineGrid grid = gridOf(bspline);

  BSplineMutualInformationCost cost(
    double bendingWeightMm2, const double (&affine)[3][4] = kIdentity) const
  {
    return BSplineMutualInformationCost(
      drawBSplineSamples(fixed, bspline->GetCoefficientImages()[0], 4000, 11), moving, affine, grid,
      16, bendingWeightMm2);
  }

  /// Coefficients that displace every point by `s` (a cubic B-spline's
  /// weights sum to one).
  vnl_vector<double> constant(const double s[3]) const
  {
    vnl_vector<double> c(static_cast<unsigned>(3 * grid.nodes()));
    for (unsigned d = 0; d < 3; ++d)
    {
      for (long n = 0; n < grid.nodes(); ++n)
      {
        c[static_cast<unsigned>(d * grid.nodes() + n)] = s[d];
      }
    }
    return c;
  }
};

double valueAt(BSplineMutualInformationCost& cost, const vnl_vector<double>& c)
{
  double f = 0.0;
  cost.compute(c, &f, nullptr);
  return f;
}

} // namespace

TEST(BSplineMutualInformationCost, ItsGradientIsTheDerivativeOfItsValue)
{
  const ShiftedPattern world;
  BSplineMutualInformationCost cost = world.cost(5.0);
  // Somewhere that is neither the identity nor the truth, with curvature.
  vnl_vector<double> c(static_cast<unsigned>(3 * world.grid.nodes()));
  for (unsigned p = 0; p < c.size(); ++p)
  {
    c[p] = 0.4 * std::sin(0.7 * p) + (p < c.size() / 3 ? 0.6 : 0.0);
  }
  double f = 0.0;
  vnl_vector<double> gradient;
  cost.compute(c, &f, &gradient);
  ASSERT_EQ(gradient.size(), c.size());
  int checked = 0;
  for (unsigned p = 0; p < c.size(); p += 7)
  {
    const double h = 1e-4;
    vnl_vector<double> plus = c;
    vnl_vector<double> minus = c;
    plus[p] += h;
    minus[p] -= h;
    const double numeric = (valueAt(cost, plus) - valueAt(cost, minus)) / (2.0 * h);
    EXPECT_NEAR(gradient[p], numeric, 1e-3 * std::abs(numeric) + 1e-7) << "coefficient " << p;
    checked += std::abs(numeric) > 1e-5 ? 1 : 0;
  }
  EXPECT_GT(checked, 20) << "most checked coefficients move the cost";
}

TEST(BSplineMutualInformationCost, IsLowestAtTheShiftThatCarriesTheFixedImageOntoTheMoving)
{
  const ShiftedPattern world;
  BSplineMutualInformationCost cost = world.cost(0.0);
  const double* none = kNoShiftMm;
  const double twice[3] = { 2 * kShiftMm[0], 2 * kShiftMm[1], 2 * kShiftMm[2] };
  const double opposite[3] = { -kShiftMm[0], -kShiftMm[1], -kShiftMm[2] };
  const double atTruth = valueAt(cost, world.constant(kShiftMm));
  EXPECT_LT(atTruth, valueAt(cost, world.constant(none)));
  EXPECT_LT(atTruth, valueAt(cost, world.constant(twice)));
  EXPECT_LT(atTruth, valueAt(cost, world.constant(opposite)));
  // From the identity, the steepest descent points towards the shift.
  vnl_vector<double> gradient;
  cost.compute(world.constant(none), nullptr, &gradient);
  EXPECT_LT(dot_product(gradient, world.constant(kShiftMm)), 0.0);
}

TEST(BSplineMutualInformationCost, AnAffineMapBeforeTheMovingImageIsPartOfTheTransform)
{
  // The same shift given as the affine map instead of the coefficients.
  const ShiftedPattern world;
  const double shifted[3][4] = { { 1, 0, 0, kShiftMm[0] }, { 0, 1, 0, kShiftMm[1] },
    { 0, 0, 1, kShiftMm[2] } };
  BSplineMutualInformationCost byAffine = world.cost(0.0, shifted);
  BSplineMutualInformationCost byCoefficients = world.cost(0.0);
  EXPECT_NEAR(valueAt(byAffine, world.constant(kNoShiftMm)),
    valueAt(byCoefficients, world.constant(kShiftMm)), 1e-9);
}

TEST(
  BSplineMutualInformationCost, BendingEnergyIsZeroForAnAffineFieldAndTheSquaredCurvatureOtherwise)
{
  const ShiftedPattern world;
  const BSplineMutualInformationCost cost = world.cost(1.0);
  const BSplineGrid& g = world.grid;
  vnl_vector<double> linear(static_cast<unsigned>(3 * g.nodes()));
  vnl_vector<double> bent(static_cast<unsigned>(3 * g.nodes()), 0.0);
  for (long k = 0; k < g.size[2]; ++k)
  {
    for (long j = 0; j < g.size[1]; ++j)
    {
      for (long i = 0; i < g.size[0]; ++i)
      {
        const long n = i + g.size[0] * (j + g.size[1] * k);
        const double x = i * g.spacingMm[0], y = j * g.spacingMm[1], z = k * g.spacingMm[2];
        for (long d = 0; d < 3; ++d)
        {
          linear[static_cast<unsigned>(d * g.nodes() + n)] = 0.1 * x - 0.2 * y + 0.05 * (d + 1) * z;
        }
        // u_y = 0.01 x^2: d2u_y/dx2 = 0.02 /mm, the only second derivative.
        bent[static_cast<unsigned>(g.nodes() + n)] = 0.01 * x * x;
      }
    }
  }
  EXPECT_NEAR(cost.bendingEnergy(linear, 1.0, nullptr), 0.0, 1e-12);
  EXPECT_NEAR(cost.bendingEnergy(bent, 1.0, nullptr), 0.02 * 0.02, 1e-12);
  // Its gradient, weighted, added to a gradient (central differences are exact for a quadratic).
  vnl_vector<double> gradient(bent.size(), 0.0);
  cost.bendingEnergy(bent, 3.0, &gradient);
  for (unsigned p = 0; p < bent.size(); p += 5)
  {
    vnl_vector<double> plus = bent;
    vnl_vector<double> minus = bent;
    plus[p] += 0.1;
    minus[p] -= 0.1;
    const double numeric = 3.0 *
      (cost.bendingEnergy(plus, 1.0, nullptr) - cost.bendingEnergy(minus, 1.0, nullptr)) / 0.2;
    EXPECT_NEAR(gradient[p], numeric, 1e-10) << "coefficient " << p;
  }
}

TEST(BSplineMutualInformationCost, SamplesAreRepeatableAndTheirWeightsSumToOne)
{
  const ShiftedPattern world;
  const auto* grid = world.bspline->GetCoefficientImages()[0].GetPointer();
  const std::vector<BSplineSample> a = drawBSplineSamples(world.fixed, grid, 500, 3);
  const std::vector<BSplineSample> b = drawBSplineSamples(world.fixed, grid, 500, 3);
  ASSERT_EQ(a.size(), 500u) << "the grid's support covers the whole image";
  for (std::size_t s = 0; s < a.size(); ++s)
  {
    EXPECT_EQ(a[s].xMm[0], b[s].xMm[0]);
    EXPECT_EQ(a[s].firstNode, b[s].firstNode);
    double sum = 0.0;
    for (float w : a[s].weights)
    {
      sum += w;
    }
    EXPECT_NEAR(sum, 1.0, 1e-5);
    EXPECT_NEAR(a[s].fixedValue, pattern(a[s].xMm[0], a[s].xMm[1], a[s].xMm[2]), 40.0)
      << "the fixed value is interpolated at the sample, not taken at a voxel centre";
  }
}

TEST(BSplineMutualInformationCost, RefusesATransformThatLeavesTheMovingImage)
{
  const ShiftedPattern world;
  const double away[3][4] = { { 1, 0, 0, 500.0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } };
  BSplineMutualInformationCost cost = world.cost(0.0, away);
  try
  {
    valueAt(cost, world.constant(kNoShiftMm));
    FAIL() << "no error";
  }
  catch (const itk::ExceptionObject& e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("too many samples map outside the moving image"),
      std::string::npos)
      << e.GetDescription();
  }
}
