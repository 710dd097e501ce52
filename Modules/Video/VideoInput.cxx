#include <vimlop/Video/VideoInput.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Video/ColmapImport.h>
#include <vimlop/Video/FrameUndistorter.h>
#include <vimlop/Video/StructureFromMotion.h>

#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>

namespace vimlop
{

std::vector<cv::Mat> idealFrames(const FrameSequence& sequence, const PinholeCamera& k,
  const std::string& framesPath, const std::string& intrinsicsPath, std::ostream* log)
{
  if (k.widthPx != sequence.widthPx() || k.heightPx != sequence.heightPx())
  {
    throwFileError(intrinsicsPath,
      "the intrinsics are for " + std::to_string(k.widthPx) + "x" + std::to_string(k.heightPx) +
        " pixels but the frames in '" + framesPath + "' are " + std::to_string(sequence.widthPx()) +
        "x" + std::to_string(sequence.heightPx()));
  }
  // SfM and contours work on ideal pinhole frames: lens distortion is removed first.
  const FrameUndistorter undistorter(k);
  if (undistorter.distorts() && log)
  {
    *log << "vimlop: note: undistorting the frames with the intrinsics' "
         << (k.lensModel == LensModel::Fisheye ? "fisheye " : "") << "distortion coefficients\n";
  }
  std::vector<cv::Mat> frames;
  for (int f = 0; f < sequence.size(); ++f)
  {
    frames.push_back(undistorter.undistort(sequence.frame(f)));
  }
  return frames;
}

SfmReconstruction reconstructFrames(const std::vector<cv::Mat>& frames,
  const std::vector<std::string>& names, const PinholeCamera& ideal,
  const std::string& colmapFolder, int threads, std::ostream* log, const cv::Mat& featureMask)
{
  SfmReconstruction sfm;
  if (colmapFolder.empty())
  {
    StructureFromMotionOptions options;
    options.threads = threads;
    StructureFromMotion engine(options);
    engine.setFeatureMask(featureMask);
    sfm = engine.reconstruct(frames, ideal, names, log);
  }
  else
  {
    std::vector<std::string> warnings;
    sfm = readColmapModel(colmapFolder, ColmapFormat::Automatic, names, 0.5, &warnings);
    for (const std::string& w : warnings)
    {
      if (log)
      {
        *log << "vimlop: warning: " << w << "\n";
      }
    }
  }
  for (const SfmReconstruction::Frame& f : sfm.frames)
  {
    if (!f.registered && log)
    {
      *log << "vimlop: warning: frame '" << f.name << "' was not registered; it is dropped\n";
    }
  }
  return sfm;
}

double frameTimeS(int frameId, int firstFrameId, double fps, double offsetS)
{
  return offsetS + static_cast<double>(frameId - firstFrameId) / fps;
}

std::vector<double> frameTimesS(const std::vector<int>& frameIds, double fps, double offsetS)
{
  std::vector<double> times;
  for (int id : frameIds)
  {
    times.push_back(frameTimeS(id, frameIds.front(), fps, offsetS));
  }
  return times;
}

double framesPerSecondOf(double recordedFps, double fps)
{
  return fps > 0.0 ? fps : (recordedFps > 0.0 ? recordedFps : defaultFramesPerSecond);
}

std::vector<double> frameTimesS(const std::vector<int>& frameIds,
  const std::vector<double>& timestampsS, double recordedFps, double fps, double offsetS,
  std::string* warning)
{
  if (!std::isfinite(fps) || fps < 0.0)
  {
    throw Error(
      "the frame rate must be positive (or 0: from the frames), got " + std::to_string(fps));
  }
  const bool stamped = !timestampsS.empty() && timestampsS.size() == frameIds.size();
  if (stamped && fps == 0.0)
  {
    std::vector<double> times;
    for (const double t : timestampsS)
    {
      times.push_back(offsetS + t);
    }
    return times;
  }
  if (warning && fps > 0.0 && recordedFps > 0.0 && std::abs(fps / recordedFps - 1.0) > 0.01)
  {
    std::ostringstream text;
    text << "the frame rate given, " << fps << " fps, disagrees with the "
         << (stamped ? "frames' own timestamps" : "video's") << " (" << recordedFps
         << " fps); the frame times follow the rate given";
    *warning = text.str();
  }
  if (warning && fps == 0.0 && recordedFps == 0.0 && frameIds.size() > 1)
  {
    std::ostringstream text;
    text << "the frames record no times: they are taken " << defaultFramesPerSecond
         << " fps apart (give the video's frame rate, e.g. --fps 25)";
    *warning = text.str();
  }
  // An overridden rate keeps the clock: the first frame keeps its time.
  return frameTimesS(
    frameIds, framesPerSecondOf(recordedFps, fps), offsetS + (stamped ? timestampsS.front() : 0.0));
}

TrackerScaleResult scaleFromTracker(const TrackerTrajectory& tracker, const SfmReconstruction& sfm,
  const std::vector<double>& timesS, std::ostream* log)
{
  std::vector<Eigen::Vector3d> centres;
  for (const SfmReconstruction::Frame& f : sfm.frames)
  {
    centres.push_back(f.registered
        ? f.cameraToSfm.centre
        : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  }
  const TrackerScaleResult scale = estimateTrackerScale(tracker, timesS, centres);
  for (const std::string& w : scale.warnings)
  {
    if (log)
    {
      *log << "vimlop: warning: " << w << "\n";
    }
  }
  return scale;
}

} // namespace vimlop
