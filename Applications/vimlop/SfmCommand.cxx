#include "CommandLine.h"
#include "Commands.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Video/IntrinsicsIO.h>
#include <vimlop/Video/SfmReconstructionIO.h>
#include <vimlop/Video/VideoInput.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

namespace vimlop
{

namespace
{

struct SfmOptions
{
  std::string frames;
  std::string intrinsics;
  std::string colmap;
  std::string out;
  std::string tracker;
  std::string trackerTransform;
  double fps = 0.0;
  double timeOffset = 0.0;
  int threads = 0;
  bool json = false;
};

void runSfm(const SfmOptions& o)
{
  // The tracker file is checked before the work, so that a bad one fails fast.
  std::vector<std::string> trackerWarnings;
  std::optional<TrackerTrajectory> tracker;
  if (!o.trackerTransform.empty())
  {
    tracker = TrackerTrajectory::readTrackedSequence(
      o.tracker.empty() ? o.frames : o.tracker, o.trackerTransform, &trackerWarnings);
  }
  else if (!o.tracker.empty())
  {
    tracker = TrackerTrajectory::readCsv(o.tracker, &trackerWarnings);
  }
  for (const std::string& w : trackerWarnings)
  {
    std::cerr << "vimlop: warning: " << w << "\n";
  }
  SfmReconstruction sfm;
  // The frames' ids (their file numbers) or timestamps give their times on the tracker's clock.
  std::vector<int> ids;
  std::vector<double> timestampsS;
  double recordedFps = 0.0;
  if (!o.colmap.empty())
  {
    std::vector<std::string> names;
    if (!o.frames.empty())
    {
      const FrameSequence sequence = FrameSequence::load(o.frames);
      names = sequence.names();
      ids = sequence.ids();
      timestampsS = sequence.timestampsS();
      recordedFps = sequence.framesPerSecond();
    }
    sfm = reconstructFrames({}, names, PinholeCamera(), o.colmap, 0, &std::cerr);
  }
  else
  {
    if (o.frames.empty() || o.intrinsics.empty())
    {
      throw Error("give --frames and --intrinsics (or --colmap to import a COLMAP model)");
    }
    const PinholeCamera k = readIntrinsics(o.intrinsics);
    const FrameSequence sequence = FrameSequence::load(o.frames);
    ids = sequence.ids();
    timestampsS = sequence.timestampsS();
    recordedFps = sequence.framesPerSecond();
    if (!sequence.idGaps().empty())
    {
      std::cerr << "vimlop: warning: missing from the frames' numbering: " << sequence.idGaps()
                << "\n";
    }
    if (tracker)
    {
      checkTrackerOverlap(
        *tracker, frameTimesS(ids, timestampsS, recordedFps, o.fps, o.timeOffset, nullptr));
    }
    const std::vector<cv::Mat> frames =
      idealFrames(sequence, k, o.frames, o.intrinsics, &std::cerr);
    PinholeCamera ideal = k;
    ideal.removeDistortion();
    sfm = reconstructFrames(frames, sequence.names(), ideal, "", o.threads, &std::cerr);
  }
  if (ids.size() != sfm.frames.size())
  {
    timestampsS.clear();
    ids.resize(sfm.frames.size());
    for (std::size_t f = 0; f < ids.size(); ++f)
    {
      ids[f] = static_cast<int>(f);
    }
  }
  CommandSummary summary;
  if (tracker)
  {
    std::string warning;
    const std::vector<double> timesS =
      frameTimesS(ids, timestampsS, recordedFps, o.fps, o.timeOffset, &warning);
    if (!warning.empty())
    {
      std::cerr << "vimlop: warning: " << warning << "\n";
    }
    const TrackerScaleResult scale = scaleFromTracker(*tracker, sfm, timesS, &std::cerr);
    sfm.trackerScale = scale.scale;
    summary.lines.push_back(
      formatText("tracker scale: 1 SfM unit = %.4f mm (tracked %.2f mm over %zu frames)",
        scale.scale, scale.trackerLengthMm, scale.framesUsed.size()));
    summary.json["tracker_scale_mm_per_unit"] = scale.scale;
    summary.json["tracker_length_mm"] = scale.trackerLengthMm;
    summary.json["tracker_frames_used"] = scale.framesUsed.size();
  }
  writeSfmReconstruction(sfm, o.out);
  summary.lines.push_back(formatText(
    "SfM (%s): %d/%zu frames registered, %zu points, RMS reprojection error %.3f px; wrote '%s'",
    sfm.source.c_str(), sfm.numberOfRegisteredFrames(), sfm.frames.size(), sfm.points.size(),
    sfm.rmsReprojectionErrorPx(), o.out.c_str()));
  summary.json["source"] = sfm.source;
  summary.json["frames"] = sfm.frames.size();
  summary.json["frames_registered"] = sfm.numberOfRegisteredFrames();
  summary.json["points"] = sfm.points.size();
  summary.json["rms_reprojection_error_px"] = sfm.rmsReprojectionErrorPx();
  summary.json["out"] = o.out;
  printSummary(summary, o.json);
}

} // namespace

void addSfmCommand(CLI::App& app)
{
  auto o = std::make_shared<SfmOptions>();
  CLI::App* sfm = app.add_subcommand("sfm",
    "Structure from motion of a frame sequence: points, SfM-frame camera poses and covariances "
    "(built in, or imported from a COLMAP model)");
  sfm->add_option("--frames", o->frames,
    "folder of frames, a video file or a tracked sequence (PLUS/Slicer .igs.mha, .igs.nrrd, "
    ".seq.nrrd)");
  sfm->add_option("--intrinsics", o->intrinsics, "camera intrinsics (OpenCV YAML/JSON/XML)");
  sfm->add_option(
    "--colmap", o->colmap, "import this COLMAP sparse model folder (text or binary) instead");
  sfm->add_option("--out", o->out, "result file (VIMLOP SfM JSON)")->required();
  sfm->add_option("--tracker", o->tracker,
    "electromagnetic tracker CSV (time_s,x_mm,y_mm,z_mm), or a tracked sequence with "
    "--tracker-transform: initial scale");
  sfm->add_option("--tracker-transform", o->trackerTransform,
    "the transform of a tracked sequence that carries the scope (e.g. ProbeToTracker), from "
    "--tracker or else --frames");
  sfm
    ->add_option("--fps", o->fps,
      "frame rate, for the frame times on the tracker's clock; overrides the frames' own "
      "timestamps or video rate (default: the frames' own, else 30)")
    ->check(CLI::PositiveNumber);
  sfm
    ->add_option(
      "--time-offset", o->timeOffset, "time of the first frame on the tracker's clock, s")
    ->capture_default_str();
  sfm->add_option("--threads", o->threads, "threads, 0 for all cores (results do not depend on it)")
    ->capture_default_str()
    ->check(CLI::Range(0, 1024));
  addJsonFlag(*sfm, o->json);
  sfm->callback([o] { runSfm(*o); });
}

} // namespace vimlop
