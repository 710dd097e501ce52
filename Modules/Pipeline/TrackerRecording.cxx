#include <vimlop/Pipeline/TrackerRecording.h>

#include <vimlop/Core/CoordinateFrames.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Imaging/LinearTransformIO.h>
#include <vimlop/Video/FrameSequence.h>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <vector>

namespace vimlop
{

std::optional<TrackerTrajectory> readTrackerRecording(const std::string& trackerPath,
  const std::string& transformName, const std::string& framesPath,
  const std::function<void(const std::string&)>& warn)
{
  std::vector<std::string> warnings;
  std::optional<TrackerTrajectory> tracker;
  if (!transformName.empty())
  {
    tracker = TrackerTrajectory::readTrackedSequence(
      trackerPath.empty() ? framesPath : trackerPath, transformName, &warnings);
  }
  else if (!trackerPath.empty())
  {
    if (FrameSequence::isTrackedSequenceName(trackerPath))
    {
      throw Error("'" + trackerPath +
        "' is a tracked sequence: name the transform that carries the scope "
        "(--tracker-transform, e.g. ProbeToTracker)");
    }
    tracker = TrackerTrajectory::readCsv(trackerPath, &warnings);
  }
  for (const std::string& w : warnings)
  {
    warn(w);
  }
  return tracker;
}

Eigen::Matrix4d readTrackerToCT(const std::string& path)
{
  const AffineMatrix4 m = readLinearTransformFile(path);
  return intoLpsFromSlicerFile(
    Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(m.data()));
}

std::optional<TrackerPrior> trackerPriorAt(
  const TrackerTrajectory& recording, const Eigen::Matrix4d& trackerToCT, double timeS)
{
  const std::optional<Eigen::Vector3d> tip = recording.positionAt(timeS);
  if (!tip)
  {
    return std::nullopt;
  }
  TrackerPrior prior((trackerToCT * tip->homogeneous()).head<3>());
  if (const std::optional<Eigen::Matrix4d> sensor = recording.poseAt(timeS))
  {
    prior.rotationCT = nearestRotation((trackerToCT * *sensor).topLeftCorner<3, 3>().eval());
  }
  return prior;
}

} // namespace vimlop
