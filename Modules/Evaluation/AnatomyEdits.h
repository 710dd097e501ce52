#ifndef vimlop_AnatomyEdits_h
#define vimlop_AnatomyEdits_h

#include <vimlop/Imaging/CTVolume.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief What a local edit of the anatomy does inside its sphere.
enum class AnatomyEditKind
{
  /// Tissue grows into the air by the depth: a larger turbinate, a septum
  /// deviated into the passage.
  GrowTissue,
  /// Tissue within the depth of the air becomes air: a smaller turbinate.
  ShrinkTissue,
  /// All the air becomes fluid: a filled sinus, a blocked passage.
  FillAir
};

/// @brief "grow", "shrink" or "fill".
std::string anatomyEditKindName(AnatomyEditKind kind);

/// @brief Settings of the local edits of P4's harder pairs (issue 18).
struct AnatomyEditOptions
{
  /// Number of edits. Default 0: none. In [0, 20].
  int count = 0;
  /// Radius of each edit's sphere, mm. Default 6 (a turbinate's width). In [1, 20].
  double radiusMm = 6.0;
  /// How far tissue grows or shrinks, mm. Default 2. In [0.5, 5].
  double depthMm = 2.0;
  /// Voxels below this are air. Default -400 HU (the segmentation's threshold).
  double airThresholdHU = -400.0;
  /// What grown tissue and fluid become, HU. Default 40 (soft tissue).
  double tissueHU = 40.0;
  /// Seed of the places. Default 1.
  std::uint32_t seed = 1;

  /**
   * @brief Checks the ranges.
   * @throws vimlop::Error naming the first value out of range.
   */
  void validate() const;
};

/// @brief One edit: its kind and its sphere's centre (CT frame, mm).
struct AnatomyEdit
{
  AnatomyEditKind kind = AnatomyEditKind::GrowTissue;
  std::array<double, 3> centreMm{ 0.0, 0.0, 0.0 };
};

/**
 * @brief `options.count` edits centred on points of the airway wall
 * `wallPointsMm` drawn with the seed (a 32-bit Mersenne Twister's raw output,
 * the same on every platform), each at least two radii plus two depths from
 * the others so that no two touch; the kinds take turns: grow, shrink, fill.
 * Fewer when the wall has no room for more.
 * @throws vimlop::Error for options out of range.
 */
std::vector<AnatomyEdit> placeAnatomyEdits(
  const std::vector<std::array<double, 3>>& wallPointsMm, const AnatomyEditOptions& options);

/**
 * @brief Applies the edits to `ct` inside their spheres: grow sets air
 * voxels within `depthMm` of tissue to `tissueHU`, shrink sets tissue voxels
 * within `depthMm` of air to -1000 HU, fill sets air voxels to `tissueHU`.
 * @return The number of voxels changed.
 */
std::size_t applyAnatomyEdits(
  CTVolume& ct, const std::vector<AnatomyEdit>& edits, const AnatomyEditOptions& options);

/// @brief True when `pointMm` lies within radius plus depth of an edit's centre.
bool nearAnatomyEdit(const std::array<double, 3>& pointMm, const std::vector<AnatomyEdit>& edits,
  const AnatomyEditOptions& options);

} // namespace vimlop

#endif
