#ifndef vimlop_CanonicalPoses_h
#define vimlop_CanonicalPoses_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/RegistrationModel.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/**
 * @brief Settings of the canonical camera poses (V13 b); lengths in mm, CT
 * frame, angles in degrees.
 */
struct CanonicalPoseOptions
{
  /// Least distance between two positions (default 4 mm: every point of a
  /// passage is then within about 3 mm of a position, inside the capture
  /// range P3 measures, about 6 mm and 6 degrees).
  double spacingMm = 4.0;
  /// Least distance of a position to the wall (default 2 mm: the radius of a
  /// 4 mm endoscope).
  double minClearanceMm = 2.0;
  /// Free length needed ahead of the camera (default 10 mm): the scope looks
  /// along an open passage, not at a wall.
  double lookAheadMm = 10.0;
  /// View directions per position (default 2: usually both ways along the
  /// passage), each the locally most open direction, at least
  /// `minViewSeparationDeg` apart.
  int viewsPerPosition = 2;
  double minViewSeparationDeg = 60.0;
  /// Rolls about the optical axis, relative to the image "up" closest to
  /// `upCT` (default 0 only: the endoscope held upright).
  std::vector<double> rollsDeg{ 0.0 };
  /// Anatomical up in the CT frame (default +z: superior in LPS).
  Eigen::Vector3d upCT = Eigen::Vector3d::UnitZ();
  /// At most this many poses (default 20000); the deepest positions first.
  int maxPoses = 20000;
  /// Threads over the grid and the positions (default 0: all cores). The
  /// poses do not depend on it.
  int threads = 0;
  /// @throws vimlop::Error naming the first invalid field.
  void validate() const;
};

/**
 * @brief Camera poses spread evenly through the airway of `model`: positions
 * on the passages' centre lines (the points farthest from the wall first,
 * then any point `spacingMm` from those already taken, which traces the ridge
 * of the distance map), each looking along its passage (the directions with
 * the most clearance over `lookAheadMm`) with the image up towards `upCT`,
 * in each roll. Deterministic.
 * @throws vimlop::Error for invalid options or when no position has the clearance.
 */
std::vector<CameraPose> makeCanonicalPoses(
  const RegistrationModel& model, const CanonicalPoseOptions& options);

} // namespace vimlop

#endif
