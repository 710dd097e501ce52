#ifndef vimlop_TrackerPrior_h
#define vimlop_TrackerPrior_h

#include <Eigen/Core>

#include <optional>

namespace vimlop
{

/**
 * @brief What an electromagnetic tracker registered to the CT says of the
 * camera at a frame's time (the tracker's reading through the navigation
 * system's tracker-to-CT registration): a prior for EndoscopeTracker::
 * track(), not a measurement of the pose.
 */
struct TrackerPrior
{
  /// A position-only prior (a 5-DOF sensor, a CSV of tip positions);
  /// implicit, so that a tip reads as a prior.
  TrackerPrior(const Eigen::Vector3d& tip)
    : tipCT(tip)
  {
  }
  /// A 6-DOF sensor's prior: the tip and the camera's rotation.
  TrackerPrior(const Eigen::Vector3d& tip, const Eigen::Matrix3d& rotation)
    : tipCT(tip)
    , rotationCT(rotation)
  {
  }

  /// Where the tracker puts the scope's tip (its optical centre), mm, CT frame.
  Eigen::Vector3d tipCT;
  /// The camera's rotation into the CT frame that a 6-DOF sensor gives
  /// (camera axes as in CameraPose); none for a position-only tracker.
  std::optional<Eigen::Matrix3d> rotationCT;
};

} // namespace vimlop

#endif
