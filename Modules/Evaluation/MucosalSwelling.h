#ifndef vimlop_MucosalSwelling_h
#define vimlop_MucosalSwelling_h

#include <vimlop/Core/TriangleMesh.h>

#include <vector>

namespace vimlop
{

/**
 * @brief Swelling of the nasal mucosa (erectile tissue, the nasal cycle):
 * the airway wall moved into the air along its normal, in the regions where
 * the turbinates and the septum are.
 *
 * The regions are found by position along the airway (NasalCavityRegion.h),
 * in the CT frame (LPS: +y posterior, +z superior), relative to the airway
 * mesh's bounding box:
 * the nasal cavity is the part in the anterior `anteriorFraction` of its
 * length (y) and between `lowFraction` and `highFraction` of its height (z)
 * (on the bundled CT that is y 16-75 mm, z 21-63 mm: the nostrils to the
 * choanae, the nasal floor to below the ethmoid cells; the pharynx lies
 * behind it and the sinuses above). Its near-sagittal walls, those whose
 * normal lies within about 60 degrees of left-right, are the lateral walls
 * (the inferior and middle turbinates, facing the septum) and the septum's
 * sides (facing the turbinates); that is where erectile tissue is.
 *
 * The weight of a vertex is a smooth step in |n_x| (0 below 0.4, 1 above
 * 0.7) times a raised-cosine fall-off over `edgeMm` inside the box, so the
 * swelling has no step. The displacements are smoothed over the mesh
 * (`smoothingIterations` rounds of averaging each vertex with its
 * neighbours) and scaled so that the largest is `swellingMm`: a smooth
 * swelling of that height, as a nasal cycle's is over centimetres of mucosa.
 * Where the passage is narrow, each vertex moves at most `maxFreeFraction`
 * of the free length ahead of it, so that opposite walls swell towards each
 * other and close the passage but never cross (a crossed surface would turn
 * tissue into air).
 *
 * Off by default (0 mm). Realistic values: Documentation/Simulation.md.
 */
struct MucosalSwellingOptions
{
  /// Largest displacement of the wall into the air, mm (default 0: none;
  /// the nasal cycle swells the turbinates' mucosa by 1-3 mm, in [0, 5]).
  double swellingMm = 0.0;
  /// The nasal cavity as fractions of the airway's bounding box (defaults
  /// 0.6 of its length from the front, 0.2-0.6 of its height from the bottom).
  double anteriorFraction = 0.6;
  double lowFraction = 0.2;
  double highFraction = 0.6;
  /// Width of the soft edge of the region, mm (default 5).
  double edgeMm = 5.0;
  /// Rounds of neighbour averaging of the displacements (default 5).
  int smoothingIterations = 5;
  /// Largest share of the free length ahead of a vertex (along its
  /// displacement) that it moves, in (0, 0.5) (default 0.45: two opposite
  /// walls leave a tenth of the passage open).
  double maxFreeFraction = 0.45;

  /// @brief True when the surface is left as it is.
  bool isOff() const { return swellingMm == 0.0; }

  /**
   * @brief Checks the settings.
   * @throws vimlop::Error naming the first problem: a swelling outside [0, 5]
   * mm, fractions outside [0, 1] or out of order, a negative edge or
   * iteration count.
   */
  void validate() const;
};

/// @brief A swollen surface and how far each vertex moved.
struct SwollenSurface
{
  TriangleMesh mesh;
  /// Per vertex, the distance it moved into the air, mm (at most swellingMm).
  std::vector<double> displacementMm;
  /// Area of the faces whose vertices all moved by more than 10 % of the
  /// largest displacement, mm^2.
  double swollenAreaMm2 = 0.0;
};

/**
 * @brief `airway` (normals into the air) with the mucosa of the nasal cavity's
 * near-sagittal walls swollen as `options` says. With the swelling off, the
 * same mesh and zero displacements.
 * @throws vimlop::Error for invalid options, or when the region holds no
 * vertex (a mesh that is not a nasal airway in LPS).
 */
SwollenSurface swellMucosa(const TriangleMesh& airway, const MucosalSwellingOptions& options);

} // namespace vimlop

#endif
