#ifndef vimlop_VideoRegistrationPipelineInternals_h
#define vimlop_VideoRegistrationPipelineInternals_h

// Private to VIMLOP::Pipeline (not installed): the state of a
// VideoRegistrationPipeline, shared by the files that implement it so that
// each stays under the project's 600 lines.

#include <vimlop/Core/Error.h>
#include <vimlop/Pipeline/StageTimings.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>
#include <vimlop/Video/FieldOfView.h>
#include <vimlop/Video/VideoInput.h>

#include <opencv2/core/mat.hpp>

#include <future>
#include <iostream>
#include <ostream>
#include <sstream>

namespace vimlop
{

struct VideoRegistrationPipeline::Internals
{
  VideoRegistrationOptions Opts;
  std::ostream* Log = nullptr;
  std::function<void(const std::string&)> Warn = [](const std::string& text)
  { std::cerr << "vimlop: warning: " << text << "\n"; };
  Progress Report;

  std::optional<TriangleMesh> Mesh;
  /// The CT's identity (CTVolume::identity) when the model was segmented from one.
  std::map<std::string, std::string> CTIdentity;
  std::unique_ptr<RegistrationModel> Model;
  PinholeCamera Intrinsics;
  bool FramesLoaded = false;
  std::vector<cv::Mat> Frames;
  std::vector<std::string> Names;
  /// The frames' ids (FrameSequence::ids(): their file numbers), one per frame.
  std::vector<int> Ids;
  /// The frames' own times (FrameSequence::timestampsS()), one per frame, or
  /// empty, and the rate their file records (0: none).
  std::vector<double> TimestampsS;
  double RecordedFramesPerSecond = 0.0;
  /// The frames' field of view (field stop), found with the frames.
  std::optional<FieldOfView> View;
  bool ContoursDetected = false;
  std::vector<std::vector<ContourPoint>> Contours;
  std::optional<SfmReconstruction> Sfm;
  double Scale = 0.0;
  /// The loaded frames' times on the video's clock, s, and the rate given
  /// for them (0: none; both set with the scale).
  std::vector<double> TimesS;
  double GivenFramesPerSecond = 0.0;
  bool DataMade = false;
  RegistrationData Data;
  std::vector<int> FrameOf;
  std::vector<SimilarityTransform> Starts;
  StartMode Mode = StartMode::Canonical;
  int Anchor = -1;
  std::optional<MultiStartResult> Outcome;
  // prepare(): the inputs and the small files read from them.
  std::optional<VideoRegistrationInputs> Inputs;
  std::optional<TrackerTrajectory> Tracker;
  /// The tracker registered to the patient (tracker to CT, LPS), read from
  /// VideoRegistrationInputs::trackerToCTPath: the canonical starts' rotation prior.
  std::optional<Eigen::Matrix4d> TrackerToCT;
  std::vector<FramePose> StartPoses;
  /// Earlier stages' outputs given as files (read by prepare()).
  std::optional<SfmReconstruction> GivenSfm;
  struct ContoursFile
  {
    std::vector<FrameContours> frames;
    FrameContoursPictures pictures;
  };
  std::optional<ContoursFile> GivenContours;
  /// The inputs' identities (InputIdentity.h), computed beside the stages
  /// from prepare() on, so that hashing them delays no result.
  struct Identities
  {
    std::vector<RegistrationRecord::InputFile> inputs;
    std::vector<std::string> problems;
  };
  std::shared_future<Identities> InputIdentities;
  /// The time of each stage run, in order (timings()).
  StageTimings Timings;

  /// The field stop's toll on the contours, one line for detected and reused ones alike.
  void sayContourPointsDropped(size_t dropped, size_t total) const
  {
    std::ostringstream text;
    text << "field stop: " << dropped << " of " << total << " contour points ("
         << (total > 0 ? 100.0 * dropped / total : 0.0) << " %) dropped";
    this->say(text.str());
  }
  void say(const std::string& text) const
  {
    if (this->Log)
    {
      *this->Log << "vimlop register: " << text << "\n";
    }
  }

  /// Cancels (PipelineCancelled) when the progress callback says so.
  void progress(const std::string& stage, double fraction) const
  {
    if (this->Report && !this->Report(stage, fraction))
    {
      throw PipelineCancelled{};
    }
  }

  /// A registration that ends at its scale bound was probably held there: the
  /// initial scale (the tracker's) is likely wrong.
  void warnAtScaleBound() const
  {
    const double scale = this->Outcome->best.sfmToCT.scale;
    const double change = scale / this->Scale;
    if (change > 0.98 * this->Opts.scaleBoundFactor || change < 1.02 / this->Opts.scaleBoundFactor)
    {
      std::ostringstream text;
      text << "the registration ended at its scale bound (scale " << scale << ", initial "
           << this->Scale << "): the tracker's scale may be wrong";
      this->Warn(text.str());
    }
  }

  /// A flagged result from upright canonical starts may be a scope turned
  /// about its axis, which those starts cannot reach (issue 15: the
  /// simulator's freely rolled scope ends 6.3 mm and 135 deg off, flagged).
  void hintAtRoll() const
  {
    const bool rotationPrior = this->TrackerToCT && this->Tracker;
    if (this->Outcome->failure && this->Mode == StartMode::Canonical && !rotationPrior &&
      this->Opts.canonical.rollsDeg.size() < 2)
    {
      this->Warn("if the endoscope was turned about its axis, canonical starts held upright "
                 "cannot reach it: give the tracker's registration to the CT as a rotation "
                 "prior (register --tracker-to-ct), or canonical poses in several rolls "
                 "(vimlop canonical --rolls-deg, then --init canonical:FILE)");
    }
  }

  /// The loaded frames' times on the tracker's clock (frameTimesS() in
  /// VideoInput.h); the warnings about the frame rate only when a tracker
  /// makes the times matter.
  std::vector<double> frameTimes(double fps, double offsetS, bool tracked) const
  {
    std::string warning;
    std::vector<double> times = vimlop::frameTimesS(this->Ids, this->TimestampsS,
      this->RecordedFramesPerSecond, fps, offsetS, tracked ? &warning : nullptr);
    if (!warning.empty())
    {
      this->Warn(warning);
    }
    return times;
  }

  /// The canonical poses under the tracker's rotation prior (turnedAsTracked()
  /// in CanonicalStarts.h), from the tracked camera pose at the anchor frame's
  /// time; the poses as they are when the tracker has no pose then.
  std::vector<CameraPose> turnedAsTracked(const std::vector<CameraPose>& canonical) const;

  /// The ids of the SfM frames: the loaded frames' (SfM keeps every frame,
  /// registered or not, in their order).
  const std::vector<int>& idsOf(const SfmReconstruction& sfm) const
  {
    if (this->Ids.size() != sfm.frames.size())
    {
      throw Error("video registration: " + std::to_string(sfm.frames.size()) + " SfM frames for " +
        std::to_string(this->Ids.size()) + " loaded frames");
    }
    return this->Ids;
  }

  template <typename T>
  const T& need(const std::optional<T>& value, const char* what) const
  {
    if (!value)
    {
      throw Error(std::string("video registration: ") + what + " first");
    }
    return *value;
  }
  void need(bool done, const char* what) const
  {
    if (!done)
    {
      throw Error(std::string("video registration: ") + what + " first");
    }
  }
};

} // namespace vimlop

#endif
