#ifndef vimlop_MucosaTexture_h
#define vimlop_MucosaTexture_h

#include "VIMLOPRenderingModule.h"

#include <Eigen/Core>

#include <cstdint>

namespace vimlop
{

/// @brief Appearance parameters; lengths in mm (CT frame).
struct MucosaTextureOptions
{
  /// Seed of the noise lattices (default 1).
  std::uint64_t seed = 1;
  /// Base albedo, linear RGB in [0, 1] (default a pink-red).
  Eigen::Vector3d baseColour = Eigen::Vector3d(0.85, 0.42, 0.36);
  /// Size of the slow colour variation, mm (default 4).
  double patchScaleMm = 4.0;
  /// Relative amplitude of the slow variation of all channels (default 0.12).
  double patchAmplitude = 0.12;
  /// Size of the fine mottling that gives features to track, mm (default 0.7).
  double mottleScaleMm = 0.7;
  /// Relative amplitude of the mottling, per channel (default 0.08, 0.3,
  /// 0.25): it comes from blood in the mucosa, like the vessels.
  Eigen::Vector3d mottleAmplitude = Eigen::Vector3d(0.08, 0.3, 0.25);
  /// Spacing of the large and small vessel networks, mm (defaults 3 and 1.2).
  double largeVesselScaleMm = 3.0;
  double smallVesselScaleMm = 1.2;
  /// Half-width of a vessel in noise units (default 0.04: about 0.1 mm for the large ones).
  double vesselWidth = 0.04;
  /// Fraction of the light a vessel centre lets through, per channel (default 0.85, 0.45, 0.5).
  Eigen::Vector3d vesselTransmission = Eigen::Vector3d(0.85, 0.45, 0.5);
};

/**
 * @brief A procedural, solid (3-D) texture that looks like nasal mucosa: a
 * pink-red base with slow colour variation, fine mottling and a network of
 * darker blood vessels.
 *
 * The texture is a function of the position in the CT frame (mm), so it needs
 * no texture coordinates and has no seams on the airway surface; the virtual
 * endoscope evaluates it at the vertices of a finely subdivided mesh. It is
 * built from gradient noise (a lattice of pseudo-random gradients, hashed from
 * the seed, blended with a quintic fade). Vessels and the fine mottling come
 * from blood, and haemoglobin absorbs green and blue much more than red, so
 * they are strong in the green channel and faint in the red one, as in
 * endoscopic pictures.
 */
class VIMLOPRENDERING_EXPORT MucosaTexture
{
public:
  MucosaTexture();
  explicit MucosaTexture(const MucosaTextureOptions& options);

  const MucosaTextureOptions& options() const { return this->Opts; }

  /// @brief Albedo (linear RGB, each in [0, 1]) at `pointMm` (CT frame).
  Eigen::Vector3d albedo(const Eigen::Vector3d& pointMm) const;

  /**
   * @brief Gradient noise at `p` (lattice units) for lattice `octave`: smooth,
   * zero at lattice points, roughly in [-1, 1], mean about 0.
   */
  double noise(const Eigen::Vector3d& p, std::uint64_t octave) const;

private:
  /// Sum of `octaves` noise octaves (each half the size and amplitude of the last), about [-1, 1].
  double fractal(const Eigen::Vector3d& p, int octaves, std::uint64_t lattice) const;

  MucosaTextureOptions Opts;
};

} // namespace vimlop

#endif
