#ifndef vimlop_CarriedPoseErrors_h
#define vimlop_CarriedPoseErrors_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Evaluation/TemplateWarpProtocol.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

/**
 * @file CarriedPoseErrors.h
 * @brief How P4 scores camera poses carried by a template-to-patient map
 * against those the known map carries (TemplateWarpProtocol.h).
 */

namespace vimlop
{

/**
 * @brief Four points per pose, which a map known only at points (the truth,
 * elastix's) carries in its place: the centre and the centre 1 mm along each
 * CT axis.
 */
std::vector<std::array<double, 3>> poseFramePoints(const std::vector<CameraPose>& poses);

/**
 * @brief The poses carried by a map, from their frame points' images (from
 * index `first` on): the centre's image, and the rotation part of the map's
 * Jacobian from forward differences, as warpCameraPose() turns them.
 */
std::vector<CameraPose> carriedPoses(const std::vector<CameraPose>& poses,
  const std::vector<std::array<double, 3>>& images, std::size_t first);

/**
 * @brief Position and orientation errors of `estimate` against `truth`, and
 * where the pose of the largest orientation error sits in the template
 * (`templatePoses`) and how far from its wall (`templateModel`).
 */
PoseErrorSummary summarizePoseErrors(const std::vector<CameraPose>& estimate,
  const std::vector<CameraPose>& truth, const std::vector<CameraPose>& templatePoses,
  const RegistrationModel& templateModel);

/**
 * @brief The poses' orientations turned by the walls around them
 * (WallOrientationSummary): the template's wall vertices within 15 mm of each
 * centre, among the scored ones, and the truth's turn by them, found once;
 * each map is then scored against them.
 */
class WallOrientations
{
public:
  /// @brief `truthImages`: the known map's images of `vertices`;
  /// `truePoses`: the poses it carries by its Jacobian.
  WallOrientations(const std::vector<CameraPose>& poses,
    const std::vector<std::array<double, 3>>& vertices, const std::vector<std::size_t>& scored,
    const std::vector<std::array<double, 3>>& truthImages,
    const std::vector<CameraPose>& truePoses);

  /// @brief A map's orientation errors, both it and the truth turned by the
  /// walls; `images` holds the map's images of the vertices first (any
  /// points after them are ignored).
  WallOrientationSummary errorsOf(const std::vector<std::array<double, 3>>& images) const;

  /// @brief The truth's two orientations of each pose against each other:
  /// turned by the walls and by its Jacobian.
  WallOrientationSummary truthAgainstJacobian() const;

private:
  /// The rotation that best carries a pose's walls to `images`, or none for
  /// a pose without walls.
  std::vector<std::optional<Eigen::Matrix3d>> turns(
    const std::vector<std::array<double, 3>>& images) const;

  std::vector<CameraPose> Poses;
  std::vector<std::array<double, 3>> Vertices;
  std::vector<std::vector<std::size_t>> Walls;
  std::vector<std::optional<Eigen::Matrix3d>> TruthTurns;
  std::vector<CameraPose> TruePoses;
};

} // namespace vimlop

#endif
