#include <vimlop/Pipeline/VideoRegistrationPipeline.h>

// The stages an embedding program or the command line brings from elsewhere:
// contours and a reconstruction read from earlier stages' files, and COLMAP
// run as a program. The pipeline's own stages are in VideoRegistrationPipeline.cxx.

#include "VideoRegistrationPipelineInternals.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Video/ColmapImport.h>
#include <vimlop/Video/ColmapRunner.h>
#include <vimlop/Video/FieldOfView.h>

#include <opencv2/imgcodecs.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <map>

namespace vimlop
{

namespace fs = std::filesystem;

void VideoRegistrationPipeline::useContours(const std::vector<FrameContours>& contours,
  const FrameContoursPictures& pictures, const std::string& source)
{
  Internals& d = *this->Impl;
  d.need(d.FramesLoaded, "load the frames");
  const StageTimings::Stopwatch watch;
  if (pictures.widthPx > 0 &&
    (pictures.widthPx != d.Intrinsics.widthPx || pictures.heightPx != d.Intrinsics.heightPx))
  {
    throwFileError(source,
      formatText("its contours are of %dx%d pictures, the frames are %dx%d", pictures.widthPx,
        pictures.heightPx, d.Intrinsics.widthPx, d.Intrinsics.heightPx));
  }
  if (d.Intrinsics.hasDistortion() && !pictures.undistorted)
  {
    throwFileError(source,
      "its contours were detected in the frames as recorded, but the intrinsics have a lens "
      "distortion and the registration sees the frames undistorted: detect them with vimlop "
      "contours --intrinsics");
  }
  std::map<std::string, const FrameContours*> byName;
  for (const FrameContours& frame : contours)
  {
    byName[frame.name] = &frame;
  }
  const bool masked = d.View && !d.View->isEverything();
  std::vector<std::vector<ContourPoint>> kept;
  size_t dropped = 0;
  size_t total = 0;
  for (const std::string& name : d.Names)
  {
    const auto at = byName.find(name);
    if (at == byName.end())
    {
      throwFileError(source, "has no contours of the frame '" + name + "'");
    }
    kept.emplace_back();
    for (const ContourPoint& p : at->second->points)
    {
      ++total;
      if (masked && !d.View->contains(p.pixel.x(), p.pixel.y()))
      {
        ++dropped;
        continue;
      }
      kept.back().push_back(p);
    }
  }
  d.say(formatText("contours of %zu frames from '%s'", d.Names.size(), source.c_str()));
  if (masked)
  {
    d.sayContourPointsDropped(dropped, total);
  }
  d.Contours = std::move(kept);
  d.ContoursDetected = true;
  d.Timings.set("contours", watch);
}

void VideoRegistrationPipeline::reconstructWithColmap(const std::string& executable)
{
  Internals& d = *this->Impl;
  d.need(d.FramesLoaded, "load the frames");
  const StageTimings::Stopwatch watch;
  d.progress("sfm", 0.0);
  ColmapRunnerOptions options;
  options.executable = executable;
  options.threads = d.Opts.registration.threads > 0 ? d.Opts.registration.threads : -1;
  const ColmapRunner runner(options);
  runner.requireAvailable(); // before any file is written
  if (d.View && !d.View->isEverything())
  {
    d.Warn("COLMAP: its features are not masked by the field stop (the built-in SfM's are)");
  }
  // The frames as files COLMAP reads, numbered (a video's frames have no file names).
  static std::atomic<int> runs{ 0 };
  const fs::path work = fs::temp_directory_path() /
    formatText("vimlop-colmap-%ld-%d", static_cast<long>(::getpid()), runs++);
  const fs::path images = work / "images";
  std::error_code ec;
  fs::remove_all(work, ec);
  fs::create_directories(images, ec);
  if (ec)
  {
    throwFileError(images.string(), "cannot create the folder (" + ec.message() + ")");
  }
  std::vector<std::string> fileNames;
  for (size_t f = 0; f < d.Frames.size(); ++f)
  {
    fileNames.push_back(formatText("%06zu.png", f));
    if (!cv::imwrite((images / fileNames.back()).string(), d.Frames[f]))
    {
      throwFileError((images / fileNames.back()).string(), "cannot write the frame");
    }
  }
  PinholeCamera ideal = d.Intrinsics;
  ideal.removeDistortion();
  d.say("SfM: COLMAP on " + std::to_string(d.Frames.size()) + " frames in '" + work.string() + "'");
  SfmReconstruction sfm;
  try
  {
    // COLMAP's own folder beside the images: the runner starts it afresh.
    const std::string model = runner.run(images.string(), ideal, (work / "colmap").string());
    std::vector<std::string> warnings;
    sfm = readColmapModel(model, ColmapFormat::Automatic, fileNames, 0.5, &warnings);
    for (const std::string& w : warnings)
    {
      d.Warn(w);
    }
  }
  catch (const Error& e)
  {
    throw Error(std::string(e.what()) + " (COLMAP's files are kept in '" + work.string() + "')");
  }
  for (size_t f = 0; f < sfm.frames.size(); ++f)
  {
    sfm.frames[f].name = d.Names[f];
  }
  fs::remove_all(work, ec);
  if (sfm.numberOfRegisteredFrames() < 2 || sfm.points.size() < 10)
  {
    throw Error("COLMAP registered " + std::to_string(sfm.numberOfRegisteredFrames()) +
      " frames and " + std::to_string(sfm.points.size()) + " points; too few to register");
  }
  d.say(formatText("SfM (COLMAP): %d of %zu frames, %zu points", sfm.numberOfRegisteredFrames(),
    sfm.frames.size(), sfm.points.size()));
  d.Sfm = std::move(sfm);
  d.Timings.set("sfm", watch);
  d.progress("sfm", 1.0);
}

void VideoRegistrationPipeline::useReconstruction(
  const SfmReconstruction& given, const std::string& source)
{
  Internals& d = *this->Impl;
  d.need(d.FramesLoaded, "load the frames");
  const StageTimings::Stopwatch watch;
  std::vector<std::string> warnings;
  SfmReconstruction sfm = given.forFrames(d.Names, &warnings);
  for (const std::string& w : warnings)
  {
    d.Warn("'" + source + "': " + w);
  }
  // The registration projects with the loaded intrinsics: SfM made with others is not this video's.
  PinholeCamera ideal = d.Intrinsics;
  ideal.removeDistortion();
  for (const SfmReconstruction::Frame& f : sfm.frames)
  {
    const PinholeCamera& k = f.intrinsics;
    const auto differs = [](double a, double b)
    { return std::abs(a - b) > 1e-6 * std::max(1.0, std::abs(b)); };
    if (f.registered &&
      (k.widthPx != ideal.widthPx || k.heightPx != ideal.heightPx || differs(k.fx, ideal.fx) ||
        differs(k.fy, ideal.fy) || differs(k.cx, ideal.cx) || differs(k.cy, ideal.cy) ||
        k.hasDistortion()))
    {
      throw Error(formatText("'%s': frame '%s' was reconstructed with other intrinsics (fx %g, fy "
                             "%g, cx %g, cy %g, %dx%d%s) than the ones given (fx %g, fy %g, cx %g, "
                             "cy %g, %dx%d, undistorted)",
        source.c_str(), f.name.c_str(), k.fx, k.fy, k.cx, k.cy, k.widthPx, k.heightPx,
        k.hasDistortion() ? ", with a lens distortion" : "", ideal.fx, ideal.fy, ideal.cx, ideal.cy,
        ideal.widthPx, ideal.heightPx));
    }
  }
  if (sfm.numberOfRegisteredFrames() < 2 || sfm.points.size() < 10)
  {
    throwFileError(source,
      "holds " + std::to_string(sfm.numberOfRegisteredFrames()) + " of the frames and " +
        std::to_string(sfm.points.size()) + " points seen in them; too few to register");
  }
  d.say(formatText("SfM from '%s': %d of %zu frames, %zu points", source.c_str(),
    sfm.numberOfRegisteredFrames(), sfm.frames.size(), sfm.points.size()));
  d.Sfm = std::move(sfm);
  d.Timings.set("sfm", watch);
}

} // namespace vimlop
