#ifndef vimlop_AnatomyEdits_h
#define vimlop_AnatomyEdits_h

#include <vimlop/Core/TriangleMesh.h>
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

/// @brief Where the edits go.
enum class AnatomyEditPlacement
{
  /// Random points of the airway wall, kinds in turn.
  RandomWall,
  /// Named sites of the nose, one kind each (placeAnatomicalEdits()).
  AnatomicalSites
};

/// @brief Settings of the local edits of P4's harder pairs (issue 18).
struct AnatomyEditOptions
{
  /// Number of edits. Default 0: none. In [0, 20]; at most 4 at anatomical sites.
  int count = 0;
  /// Random points of the wall (default) or the named sites.
  AnatomyEditPlacement placement = AnatomyEditPlacement::RandomWall;
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

/// @brief One edit: its kind, its sphere's centre (CT frame, mm) and where it is.
struct AnatomyEdit
{
  AnatomyEditKind kind = AnatomyEditKind::GrowTissue;
  std::array<double, 3> centreMm{ 0.0, 0.0, 0.0 };
  /// "wall" for a random point of the wall, else the site's name
  /// (placeAnatomicalEdits()).
  std::string site = "wall";
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
 * @brief Up to `options.count` (at most 4) edits at named sites of a nasal
 * airway in the CT frame (LPS: +x left, +y posterior, +z superior), in this
 * order:
 *  1. "septum": tissue grown on one side of the nasal septum (a deviated
 *     septum);
 *  2. "inferior turbinate": tissue grown on the lateral wall of the other
 *     passage's lower half (the larger turbinate that faces a deviation);
 *  3. "middle turbinate": tissue shrunk on the lateral wall of the first
 *     passage's upper half (a smaller turbinate);
 *  4. "maxillary sinus": the air at the floor of the sinus beside the other
 *     passage filled (fluid in a sinus).
 *
 * How the sites are found: the nasal cavity is the box of
 * NasalCavityRegion::inBounds() of the airway's bounds. Its near-sagittal
 * wall vertices (normal within about 45 degrees of left-right) tell the
 * septum: the septum is the plane x = c where most such vertices lie within
 * 3 mm and face away from it (air on both sides of a thin wall). Vertices
 * within 3 mm of c facing away from it are the septum's sides; those 4-12 mm
 * out facing back towards it, behind the front fifth of the box (the
 * vestibule), are the turbinates' medial faces, split at the box's middle
 * height into the inferior and middle turbinates. The maxillary sinus is air
 * of `ct` 12-35 mm to the side of the septum, in the box's length and
 * height or up to 10 mm below it (the sinus's floor lies below the nasal
 * floor), with air 4 mm away along each axis (a large air space, not a
 * cell) and tissue along each axis before the volume's edge (inside the
 * head); whether it joins the airway or not does not matter. The edit is
 * centred on its lowest such point, so the fluid fills the sinus's floor.
 * The seed chooses the side of the deviation and the vertex of each site,
 * at least two radii plus two depths from the edits before. A site not
 * found (or without room) is skipped, so there may be fewer edits.
 * @throws vimlop::Error for options out of range, or when the airway has no
 * near-sagittal walls in the nasal cavity (not a nasal airway in LPS).
 */
std::vector<AnatomyEdit> placeAnatomicalEdits(
  const TriangleMesh& airway, const CTVolume& ct, const AnatomyEditOptions& options);

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
