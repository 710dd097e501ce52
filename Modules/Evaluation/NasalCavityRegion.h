#ifndef vimlop_NasalCavityRegion_h
#define vimlop_NasalCavityRegion_h

#include <Eigen/Core>

namespace vimlop
{

/**
 * @brief Where the nasal cavity lies in a nasal airway mesh's bounding box,
 * CT frame (LPS: +y posterior, +z superior): the anterior `anteriorFraction`
 * of its length (y) and between `lowFraction` and `highFraction` of its
 * height (z). On the bundled CT that is y 16-75 mm, z 21-63 mm: the nostrils
 * to the choanae, the nasal floor to below the ethmoid cells; the pharynx
 * lies behind and the sinuses above. The swelling of the mucosa and the
 * anatomical edits find their sites in it.
 */
struct NasalCavityRegion
{
  double yFrontMm = 0.0;
  double yBackMm = 0.0;
  double zLowMm = 0.0;
  double zHighMm = 0.0;

  /// @brief The region in the bounds (columns: low and high corners, mm).
  static NasalCavityRegion inBounds(const Eigen::Matrix<double, 3, 2>& bounds,
    double anteriorFraction = 0.6, double lowFraction = 0.2, double highFraction = 0.6)
  {
    const Eigen::Vector3d low = bounds.col(0);
    const Eigen::Vector3d extent = bounds.col(1) - low;
    return { low.y(), low.y() + anteriorFraction * extent.y(), low.z() + lowFraction * extent.z(),
      low.z() + highFraction * extent.z() };
  }

  /// @brief True when the point lies in the region's y and z ranges.
  bool contains(const Eigen::Vector3d& pointMm) const
  {
    return pointMm.y() >= yFrontMm && pointMm.y() <= yBackMm && pointMm.z() >= zLowMm &&
      pointMm.z() <= zHighMm;
  }
};

} // namespace vimlop

#endif
