#include <vimlop/Rendering/MucosaTexture.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

namespace
{

/// A 64-bit mix (the finaliser of a splitmix generator): every input bit
/// affects every output bit, so neighbouring lattice points get unrelated values.
std::uint64_t mix(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

/// Unit gradient of lattice point (i, j, k): a hashed direction from the
/// 12 edge midpoints of a cube, which have no preferred axis.
Eigen::Vector3d gradient(std::int64_t i, std::int64_t j, std::int64_t k, std::uint64_t seed)
{
  static const double s = 1.0 / std::sqrt(2.0);
  static const Eigen::Vector3d directions[12] = { { s, s, 0 }, { -s, s, 0 }, { s, -s, 0 },
    { -s, -s, 0 }, { s, 0, s }, { -s, 0, s }, { s, 0, -s }, { -s, 0, -s }, { 0, s, s },
    { 0, -s, s }, { 0, s, -s }, { 0, -s, -s } };
  std::uint64_t h = mix(seed);
  h = mix(h ^ static_cast<std::uint64_t>(i));
  h = mix(h ^ static_cast<std::uint64_t>(j));
  h = mix(h ^ static_cast<std::uint64_t>(k));
  return directions[h % 12];
}

/// Quintic fade 6t^5 - 15t^4 + 10t^3: zero first and second derivatives at
/// 0 and 1, so the noise has no visible lattice creases.
double fade(double t)
{
  return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

double smoothstep(double edge0, double edge1, double x)
{
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

} // namespace

MucosaTexture::MucosaTexture()
  : MucosaTexture(MucosaTextureOptions())
{
}

MucosaTexture::MucosaTexture(const MucosaTextureOptions& options)
  : Opts(options)
{
}

double MucosaTexture::noise(const Eigen::Vector3d& p, std::uint64_t octave) const
{
  const std::uint64_t seed = mix(this->Opts.seed * 0x100000001b3ull + octave);
  const Eigen::Vector3d floor(std::floor(p.x()), std::floor(p.y()), std::floor(p.z()));
  const Eigen::Vector3d f = p - floor;
  const auto i = static_cast<std::int64_t>(floor.x());
  const auto j = static_cast<std::int64_t>(floor.y());
  const auto k = static_cast<std::int64_t>(floor.z());
  double corner[8];
  for (int c = 0; c < 8; ++c)
  {
    const int di = c & 1;
    const int dj = (c >> 1) & 1;
    const int dk = (c >> 2) & 1;
    corner[c] = gradient(i + di, j + dj, k + dk, seed).dot(f - Eigen::Vector3d(di, dj, dk));
  }
  const double u = fade(f.x());
  const double v = fade(f.y());
  const double w = fade(f.z());
  auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
  const double x00 = lerp(corner[0], corner[1], u);
  const double x10 = lerp(corner[2], corner[3], u);
  const double x01 = lerp(corner[4], corner[5], u);
  const double x11 = lerp(corner[6], corner[7], u);
  // Gradient noise with unit gradients stays within about ±0.9; scale to ±1.
  return 1.1 * lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

double MucosaTexture::fractal(const Eigen::Vector3d& p, int octaves, std::uint64_t lattice) const
{
  double sum = 0.0;
  double amplitude = 1.0;
  double norm = 0.0;
  double frequency = 1.0;
  for (int o = 0; o < octaves; ++o)
  {
    sum += amplitude * this->noise(frequency * p, lattice * 16 + static_cast<std::uint64_t>(o));
    norm += amplitude;
    amplitude *= 0.5;
    frequency *= 2.03; // not 2: octaves whose lattices coincide would show a grid
  }
  return sum / norm;
}

Eigen::Vector3d MucosaTexture::albedo(const Eigen::Vector3d& pointMm) const
{
  const MucosaTextureOptions& o = this->Opts;
  Eigen::Vector3d colour = o.baseColour;

  // Slow variation: brightness and a shift between pink and a paler yellow.
  const double patch = this->fractal(pointMm / o.patchScaleMm, 2, 1);
  const double hue =
    this->fractal(pointMm / o.patchScaleMm + Eigen::Vector3d(17.3, 5.1, 9.7), 2, 2);
  colour *= 1.0 + o.patchAmplitude * patch;
  colour += 0.06 * hue * Eigen::Vector3d(0.2, 0.9, 0.6);

  // Fine mottling (glands, surface roughness): the features that SfM tracks.
  const double mottle = this->fractal(pointMm / o.mottleScaleMm, 3, 3);
  colour = colour.cwiseProduct(Eigen::Vector3d::Ones() + mottle * o.mottleAmplitude);

  // Vessels: the zero set of a noise field is a network of smooth curves;
  // darken near it. Small vessels are fainter and only appear in patches.
  auto vessel = [&](double scaleMm, std::uint64_t lattice, double widthFactor)
  {
    const double n = this->fractal(pointMm / scaleMm, 2, lattice);
    const double width = o.vesselWidth * widthFactor;
    return 1.0 - smoothstep(0.4 * width, width, std::abs(n));
  };
  const double large = vessel(o.largeVesselScaleMm, 4, 1.0);
  const double presence = smoothstep(-0.1, 0.3, this->fractal(pointMm / 5.0, 1, 6));
  const double small = 0.7 * presence * vessel(o.smallVesselScaleMm, 5, 1.2);
  const double density = std::max(large, small);
  for (int c = 0; c < 3; ++c)
  {
    colour[c] *= 1.0 - density * (1.0 - o.vesselTransmission[c]);
  }
  return colour.cwiseMax(0.0).cwiseMin(1.0);
}

} // namespace vimlop
