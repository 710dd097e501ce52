#ifndef vimlop_TrackerRecording_h
#define vimlop_TrackerRecording_h

#include <vimlop/Pipeline/TrackerPrior.h>
#include <vimlop/Video/TrackerTrajectory.h>

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>

namespace vimlop
{

/**
 * @brief The electromagnetic tracker's recording that `vimlop register` and
 * `vimlop track` are given: the transform `transformName` of a tracked
 * sequence (`trackerPath`, or `framesPath` when that is empty) when a
 * transform is named, else the CSV `trackerPath`; none when neither is
 * given. Each reader's warnings (dropped rows, glitches) go to `warn`.
 * @throws vimlop::Error naming the file for an unreadable recording, or a
 * tracked sequence given as a CSV (no transform named).
 */
std::optional<TrackerTrajectory> readTrackerRecording(const std::string& trackerPath,
  const std::string& transformName, const std::string& framesPath,
  const std::function<void(const std::string&)>& warn);

/**
 * @brief The tracker registered to the patient, as 3D Slicer saves its
 * tracker-to-RAS transform (an ITK transform file), as the map of tracker
 * points into the CT frame (LPS, mm; intoLpsFromSlicerFile()).
 * @throws vimlop::Error naming the file when it cannot be read.
 */
Eigen::Matrix4d readTrackerToCT(const std::string& path);

/**
 * @brief What `recording` says of the camera at `timeS` (its clock), carried
 * into the CT by `trackerToCT`: the tip, and the camera's rotation when the
 * recording has the sensor's (the nearest rotation to the registration's
 * linear part times the sensor's: a registration with scale or shear turns
 * no camera into a non-rotation); none outside the recording.
 */
std::optional<TrackerPrior> trackerPriorAt(
  const TrackerTrajectory& recording, const Eigen::Matrix4d& trackerToCT, double timeS);

} // namespace vimlop

#endif
