#ifndef vimlop_AirwaySegmentation_h
#define vimlop_AirwaySegmentation_h

#include <vimlop/Imaging/CTVolume.h>
#include <vimlop/Imaging/ProgressCallback.h>

#include "VIMLOPImagingModule.h"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief Parameters of AirwaySegmentation::compute(); the defaults suit adult head CTs in HU.
struct AirwaySegmentationOptions
{
  /// Voxels below this are air. Default -400 HU.
  double airThresholdHU = -400.0;
  /// Voxels above this are tissue when building the head mask. Default -500 HU.
  double bodyThresholdHU = -500.0;
  /// Radius of the closing applied to the head mask before its holes are
  /// filled. Default 0 mm: no closing (see step 1).
  double bodyClosingRadiusMm = 0.0;
  /// Point (CT frame, LPS mm) inside the airway; when set, the component
  /// holding it is chosen instead of the largest. Default: unset.
  std::optional<std::array<double, 3>> seedMm;
  /// Interior air components with a voxel centre within this distance of the
  /// airway are included (sinuses behind thin walls). Default 0 mm: none.
  double sinusInclusionDistanceMm = 0.0;
  /// Smallest acceptable airway. Default 1000 mm^3 (1 cm^3); a smaller
  /// largest component means there is no airway in the volume.
  double minimumVolumeMm3 = 1000.0;
};

/**
 * @brief The nasal airway of a head CT as a label volume, and facts about it.
 *
 * Made by AirwaySegmentation::compute(), in these steps:
 *
 * 1. **Head**: voxels above `bodyThresholdHU` form the tissue mask; its
 *    largest face-connected component is the head (a head rest or cushion
 *    that touches the head may come along). Its holes are filled slice by
 *    slice across the axial axis (the index axis closest to LPS z). Slices,
 *    not 3-D: the airway is open to the outside through the nostrils and,
 *    often, the bottom of the field of view, so in 3-D it is no hole; in an
 *    axial slice it is enclosed by the face. An optional binary closing
 *    (`bodyClosingRadiusMm`) before the filling seals openings narrower than
 *    twice its radius; it is off by default because it also seals the gaps
 *    between the head and a head rest or cushion, whose air would then count
 *    as inside the head.
 * 2. **Interior air**: voxels below `airThresholdHU` inside the filled head,
 *    split into face-connected components. The outside air around the head,
 *    and the air between the head and a head rest, touch the slice borders
 *    and are never interior.
 * 3. **Choice**: with a seed point, the component holding it; otherwise the
 *    largest one. The nasal cavity, joined to the nasopharynx and to the
 *    sinuses whose ostia are open at the CT's resolution, is by far the
 *    largest air space inside a head; the next ones are typically a sinus
 *    sealed off by a thin wall or mastoid air cells (their volume is reported
 *    in `nextLargestVolumeMm3` so callers can judge the margin).
 * 4. **Sinuses** (optional): other interior air components that come within
 *    `sinusInclusionDistanceMm` of the chosen one are added.
 * 5. **Clean-up**: cavities of tissue fully enclosed by the airway (isolated
 *    voxels above the threshold) are filled, so the surface has no inner shells.
 *
 * All positions are in the CT frame (ITK physical LPS, mm).
 */
struct AirwaySegmentation
{
  /// @brief A point deep inside the airway (see deepestPoints()).
  struct InteriorPoint
  {
    /// Voxel centre, CT frame (LPS mm).
    std::array<double, 3> pointMm{ 0.0, 0.0, 0.0 };
    /// Distance from the point to the nearest airway voxel centre that
    /// touches tissue, in mm (0 for a voxel on the airway's border).
    double depthMm = 0.0;
  };

  /// 1 inside the airway, 0 elsewhere, on the CT's grid (same dims, origin,
  /// spacing and direction).
  CTVolume label;
  /// Number of airway voxels.
  std::size_t voxelCount = 0;
  /// Airway volume: voxel count times voxel volume, mm^3.
  double volumeMm3 = 0.0;
  /// Mean of the airway's voxel centres, CT frame (mm).
  std::array<double, 3> centroidMm{ 0.0, 0.0, 0.0 };
  /// Bounds of the airway's voxel centres, CT frame: x min, x max, y min, ... (mm).
  std::array<double, 6> boundsMm{ 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  /// Bounds of the head mask's voxel centres, CT frame (mm), same layout.
  std::array<double, 6> headBoundsMm{ 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  /// Number of air components inside the head.
  int interiorAirComponents = 0;
  /// Volume of the largest interior air component that was not included (mm^3; 0 if none).
  double nextLargestVolumeMm3 = 0.0;
  /// Number and total volume (mm^3) of the sinus components added in step 4.
  int includedSinuses = 0;
  double includedSinusVolumeMm3 = 0.0;
  /// How the component was chosen: "largest" or "seed".
  std::string selection;

  /**
   * @brief Segments the nasal airway of `ct` (HU, CT frame).
   *
   * @throws vimlop::Error with a one-line message when the volume is not 3-D
   * (fewer than 2 voxels along an axis) or inconsistent, a threshold selects
   * no voxel or every voxel, there is no tissue or no air inside the head,
   * the airway is smaller than `minimumVolumeMm3`, or the seed lies outside
   * the volume or in tissue.
   */
  VIMLOPIMAGING_EXPORT static AirwaySegmentation compute(const CTVolume& ct,
    const AirwaySegmentationOptions& options,
    const ProgressCallback& progress = ProgressCallback());

  /**
   * @brief Points deep inside the airway: local maxima of the label's distance
   * map, deepest first, at least `minimumSeparationMm` apart, at most `count`.
   *
   * Useful to place virtual cameras and to check surfaces (a point here must
   * be inside the airway surface with the surface's normals facing it).
   * @throws vimlop::Error if the label is empty.
   */
  VIMLOPIMAGING_EXPORT std::vector<InteriorPoint> deepestPoints(
    int count, double minimumSeparationMm) const;

  /// @brief "airway V cm^3 (largest of N interior air components; ...), centroid (x, y, z) mm
  /// LPS", as `vimlop segment` prints it.
  VIMLOPIMAGING_EXPORT std::string summaryText() const;
};

} // namespace vimlop

#endif
