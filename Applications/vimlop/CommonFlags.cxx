#include "CommandLine.h"
#include <vimlop/Core/RegistrationOptionTable.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Pipeline/ContourRelocalisation.h>
#include <vimlop/Pipeline/ContourWindowRefinement.h>
#include <vimlop/Pipeline/EndoscopeTrackerOptions.h>
#include <vimlop/Pipeline/TrackerLag.h>
#include <vimlop/Pipeline/VideoRegistrationOptionTable.h>
#include <vimlop/Pipeline/VideoRegistrationOptions.h>
#include <vimlop/Server/PoseServing.h>

#include <CLI/CLI.hpp>

namespace vimlop
{

namespace
{

template <typename T>
void addValue(CLI::App& c, const char* flag, T& field, T min, T max, const char* help)
{
  c.add_option(flag, field, help)->capture_default_str()->check(CLI::Range(min, max));
}

void addSwitch(CLI::App& c, const std::string& flag, bool& field, const char* help)
{
  // --x and --no-x; the default is what `field` holds.
  c.add_flag(flag + ",!--no-" + flag.substr(2), field,
    std::string(help) + (field ? " (default on)" : " (default off)"));
}

} // namespace

void addPipelineOptions(CLI::App& c, VideoRegistrationOptions& p)
{
  RegistrationOptions& r = p.registration;
  c.add_option_function<double>(
     "--contour-variance-px2",
     [&r](double v) { r.contourMatch.positionCovariancePx2 = v * Eigen::Matrix2d::Identity(); },
     "V5: contour position noise Σ2d (isotropic), px² (paper: 1 for video)")
    ->default_str(joinNumbers({ r.contourMatch.positionCovariancePx2(0, 0) }))
    ->check(CLI::PositiveNumber);
#define VIMLOP_REGISTRATION_FLAG(Name, Type, member, key, flag, min, max, help)                    \
  addValue<Type>(c, flag, r.member, min, max, help);
#define VIMLOP_PIPELINE_FLAG(Name, Type, member, key, flag, min, max, help)                        \
  addValue<Type>(c, flag, p.member, min, max, help);
#define VIMLOP_SWITCH_FLAG(Name, member, key, flag, help) addSwitch(c, flag, r.member, help);
  VIMLOP_REGISTRATION_VALUES(VIMLOP_REGISTRATION_FLAG)
  VIMLOP_REGISTRATION_SWITCHES(VIMLOP_SWITCH_FLAG)
  VIMLOP_VIDEO_REGISTRATION_VALUES(VIMLOP_PIPELINE_FLAG)
#undef VIMLOP_REGISTRATION_FLAG
#undef VIMLOP_PIPELINE_FLAG
#undef VIMLOP_SWITCH_FLAG
  c.add_option_function<std::string>(
     "--scale-factors",
     [&p](const std::string& list)
     { p.multiStart.scaleFactors = parseNumbers(list, "--scale-factors"); },
     "V13: variations of the initial scale per canonical start")
    ->default_str(joinNumbers(p.multiStart.scaleFactors));
  c.add_option_function<std::string>(
     "--field-stop",
     [&p](const std::string& value)
     { p.fieldOfView = FieldOfViewOptions::fromText(value, p.fieldOfView); },
     "the endoscope's field stop (black disc border): auto (detected from the frames; frames "
     "without a dark border are used whole), none, circle:U,V,R (centre and radius, px) or a "
     "mask image, white inside; contour points and SfM features outside it and within "
     "--field-stop-margin-px of its edge are not used")
    ->default_str(p.fieldOfView.toText());
}

void addCTReadOptions(CLI::App& command, CTReadOptions& options)
{
  command.add_option(
    "--series", options.dicomSeriesUID, "DICOM series UID when a folder holds several");
  command.add_flag("--resample-irregular-series", options.resampleIrregularSeries,
    "resample a DICOM series tilted by the gantry or with missing or uneven slices onto a "
    "regular grid (with a warning) instead of refusing it");
}

void addTrackingRefinementOptions(
  CLI::App& command, bool& refine, ContourWindowRefinementOptions& options)
{
  command.add_flag_callback(
    "--no-refinement", [&refine] { refine = false; },
    "do not correct the tracked poses with the contours of the last frames against the CT (the "
    "check of each pose is still made)");
  command
    .add_option("--refine-window", options.windowFrames,
      "frames whose contours are registered together to correct the tracked pose")
    ->capture_default_str()
    ->check(CLI::Range(1, 1000));
  command
    .add_option("--refine-above-px", options.minErrorPx,
      "the window is corrected only when its contours lie farther than this from the model's "
      "(median), px")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 1000.0));
  command
    .add_option("--max-correction-mm", options.maxCorrectionMm,
      "a correction that moves the camera farther than this is not applied, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  command
    .add_option("--max-correction-deg", options.maxCorrectionDeg,
      "nor one that turns it by more than this, degrees")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
}

void addEndoscopeTrackerOptions(
  CLI::App& command, EndoscopeTrackerOptions& options, TrackerLagOptions& lag)
{
  command.add_option("--max-features", options.maxFeatures, "features tracked at most")
    ->capture_default_str();
  command
    .add_option("--max-tracking-width-px", options.maxTrackingWidthPx,
      "frames wider than this are tracked halved until they fit (the tracker's pixel settings "
      "are for frames about 320 px wide)")
    ->capture_default_str();
  command
    .add_option("--inlier-px", options.inlierThresholdPx,
      "a feature agrees with a pose within this reprojection error, px")
    ->capture_default_str();
  command
    .add_option("--tracker-offset-frames", options.trackerOffsetFrames,
      "the electromagnetic tracker's error is learned from the frames tracked against the CT, "
      "over about this many frames, and taken off its readings (0: taken as it reads)")
    ->capture_default_str()
    ->check(CLI::Range(0, 100000));
  command
    .add_option("--tracker-pull", options.trackerPull,
      "while the video is not anchored to the CT, each pose is moved this fraction of the way to "
      "the electromagnetic tracker's (0: never)")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 1.0));
  command
    .add_option("--tracker-max-lag-s", lag.maxLagS,
      "the electromagnetic tracker's lag behind the frames' times is measured from the video's "
      "motion (its frames not lost), up to this much either way, and its readings are taken that "
      "much later (0: read at the frames' times)")
    ->capture_default_str()
    ->check(CLI::Range(0.0, 2.0));
}

void addTrackingRelocalisationOptions(
  CLI::App& command, bool& relocalise, ContourRelocalisationOptions& options)
{
  command.add_flag_callback(
    "--no-relocalisation", [&relocalise] { relocalise = false; },
    "do not search for the pose against the CT after the tracker was lost, when the contours "
    "disagree with the model");
  command
    .add_option("--degraded-above-px", options.degradedAbovePx,
      "a tracked frame whose contours lie farther than this from the model's (median) is "
      "reported degraded, px (or farther than 4 times the registration's contour error)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  command
    .add_option("--relocalise-search-mm", options.searchMm,
      "the relocalisation starts from the tracked pose and from it moved this far along each "
      "camera axis, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  command
    .add_option("--relocalise-search-deg", options.searchDeg,
      "and from it turned by this much about each camera axis, degrees")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
}

void addPoseServerOptions(CLI::App& command, PoseStreamServerOptions& options)
{
  command.add_option("--host", options.host, "address to listen on")->capture_default_str();
  command.add_option("--port", options.port, "TCP port (0: any free one)")->capture_default_str();
  command.add_flag("--allow-remote", options.allowRemote, "allow a non-loopback address");
  command.add_option("--max-clients", options.maxClients, "clients served at once")
    ->capture_default_str();
  command
    .add_option("--max-clients-per-address", options.maxClientsPerAddress,
      "connections kept from one address; a new one beyond it replaces that address's most idle")
    ->capture_default_str();
  command.add_option("--allow-client", options.allowedClients,
    "only this address or CIDR block may connect (repeat for more; default: any; add "
    "127.0.0.1 to keep local programs)");
  command
    .add_option("--camera-name", options.cameraName,
      "device name of the moving camera, one transform updated frame after frame (1-20 "
      "characters); also the STATUS messages' device")
    ->capture_default_str();
  command.add_flag(
    "--per-frame-names",
    [&options](std::int64_t) { options.cameraNames = CameraDeviceNames::OnePerFrame; },
    "name each frame's pose VideoCamera_<frame id> instead (one transform per frame)");
}

void addPoseServingOptions(CLI::App& command, PoseServingOptions& options)
{
  addPoseServerOptions(command, options.server);
  command
    .add_option("--duration-s", options.durationS, "stop after this many seconds (0: until Ctrl-C)")
    ->capture_default_str();
  command.add_flag("--allow-flagged", options.allowFlagged,
    "serve a result flagged as a failure too (its STATUS message says so); refused by default");
}

} // namespace vimlop
