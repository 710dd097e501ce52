#include <vimlop/Imaging/DisplacementField.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

bool DisplacementField::isValid() const
{
  return dims[0] > 0 && dims[1] > 0 && dims[2] > 0 &&
    displacements.size() == 3 * this->numberOfPoints();
}

std::array<double, 3> DisplacementField::indexToPhysical(const std::array<double, 3>& index) const
{
  std::array<double, 3> p = originMm;
  for (int row = 0; row < 3; ++row)
  {
    for (int col = 0; col < 3; ++col)
    {
      p[row] += direction[3 * row + col] * spacingMm[col] * index[col];
    }
  }
  return p;
}

std::array<double, 3> DisplacementField::physicalToIndex(const std::array<double, 3>& pointMm) const
{
  // The direction is orthonormal: its inverse is its transpose.
  std::array<double, 3> index{ 0.0, 0.0, 0.0 };
  for (int col = 0; col < 3; ++col)
  {
    double projection = 0.0;
    for (int row = 0; row < 3; ++row)
    {
      projection += direction[3 * row + col] * (pointMm[row] - originMm[row]);
    }
    index[col] = projection / spacingMm[col];
  }
  return index;
}

bool DisplacementField::contains(const std::array<double, 3>& pointMm) const
{
  const std::array<double, 3> index = this->physicalToIndex(pointMm);
  constexpr double slack = 1e-9;
  for (int a = 0; a < 3; ++a)
  {
    if (!(index[a] >= -slack && index[a] <= dims[a] - 1 + slack))
    {
      return false;
    }
  }
  return true;
}

std::array<double, 3> DisplacementField::displacementAt(const std::array<double, 3>& pointMm) const
{
  const std::array<double, 3> index = this->physicalToIndex(pointMm);
  std::array<int, 3> base{};
  std::array<double, 3> weight{};
  for (int a = 0; a < 3; ++a)
  {
    // Clamp to the grid: beyond it the border values continue.
    const double clamped = std::clamp(index[a], 0.0, static_cast<double>(dims[a] - 1));
    base[a] = std::min(static_cast<int>(std::floor(clamped)), std::max(dims[a] - 2, 0));
    weight[a] = dims[a] > 1 ? clamped - base[a] : 0.0;
  }
  std::array<double, 3> u{ 0.0, 0.0, 0.0 };
  for (int corner = 0; corner < 8; ++corner)
  {
    std::array<int, 3> at{};
    double w = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      const int step = (corner >> a) & 1;
      at[a] = std::min(base[a] + step, dims[a] - 1);
      w *= step ? weight[a] : 1.0 - weight[a];
    }
    if (w == 0.0)
    {
      continue;
    }
    const std::size_t n = static_cast<std::size_t>(at[0]) +
      static_cast<std::size_t>(dims[0]) * (at[1] + static_cast<std::size_t>(dims[1]) * at[2]);
    for (int a = 0; a < 3; ++a)
    {
      u[a] += w * displacements[3 * n + a];
    }
  }
  return u;
}

std::array<double, 3> DisplacementField::transformPoint(const std::array<double, 3>& pointMm) const
{
  const std::array<double, 3> u = this->displacementAt(pointMm);
  return { pointMm[0] + u[0], pointMm[1] + u[1], pointMm[2] + u[2] };
}

} // namespace vimlop
