#include <vimlop/Core/FileError.h>
#include <vimlop/Pipeline/VideoRegistrationPipeline.h>

#include "VideoRegistrationPipelineInternals.h"

#include <opencv2/imgcodecs.hpp>

// The pipeline's construction, settings and accessors: what each stage
// produced (VideoRegistrationPipeline.cxx holds the stages themselves).

namespace vimlop
{

VideoRegistrationPipeline::VideoRegistrationPipeline(const VideoRegistrationOptions& options)
  : Impl(std::make_unique<Internals>())
{
  options.validate();
  this->Impl->Opts = options;
}

VideoRegistrationPipeline::~VideoRegistrationPipeline() = default;

const VideoRegistrationOptions& VideoRegistrationPipeline::options() const
{
  return this->Impl->Opts;
}

void VideoRegistrationPipeline::setRegistrationOptions(const RegistrationOptions& options)
{
  options.validate();
  this->Impl->Opts.registration = options;
}

void VideoRegistrationPipeline::setLog(std::ostream* log)
{
  this->Impl->Log = log;
}

void VideoRegistrationPipeline::setWarningHandler(std::function<void(const std::string&)> handler)
{
  this->Impl->Warn = std::move(handler);
}

void VideoRegistrationPipeline::setProgress(Progress progress)
{
  this->Impl->Report = std::move(progress);
}

const TriangleMesh& VideoRegistrationPipeline::mesh() const
{
  return this->Impl->need(this->Impl->Mesh, "load the model");
}

const RegistrationModel& VideoRegistrationPipeline::model() const
{
  this->Impl->need(this->Impl->Model != nullptr, "load the model");
  return *this->Impl->Model;
}

const PinholeCamera& VideoRegistrationPipeline::intrinsics() const
{
  this->Impl->need(this->Impl->FramesLoaded, "load the frames");
  return this->Impl->Intrinsics;
}

int VideoRegistrationPipeline::numberOfFrames() const
{
  return static_cast<int>(this->Impl->Frames.size());
}

const cv::Mat& VideoRegistrationPipeline::fieldOfViewMask() const
{
  return this->Impl->need(this->Impl->View, "load the frames").mask();
}

const std::vector<std::string>& VideoRegistrationPipeline::frameNames() const
{
  return this->Impl->Names;
}

const std::vector<int>& VideoRegistrationPipeline::frameIds() const
{
  return this->Impl->Ids;
}

const std::map<std::string, std::string>& VideoRegistrationPipeline::ctIdentity() const
{
  return this->Impl->CTIdentity;
}

std::vector<RegistrationRecord::InputFile> VideoRegistrationPipeline::inputIdentities() const
{
  const Internals& d = *this->Impl;
  if (!d.InputIdentities.valid())
  {
    return {};
  }
  const Internals::Identities& identities = d.InputIdentities.get();
  for (const std::string& problem : identities.problems)
  {
    d.Warn(problem);
  }
  return identities.inputs;
}

const std::vector<std::vector<ContourPoint>>& VideoRegistrationPipeline::contours() const
{
  return this->Impl->Contours;
}

const SfmReconstruction& VideoRegistrationPipeline::sfm() const
{
  return this->Impl->need(this->Impl->Sfm, "reconstruct");
}

double VideoRegistrationPipeline::initialScale() const
{
  return this->Impl->Scale;
}

const RegistrationData& VideoRegistrationPipeline::data() const
{
  return this->Impl->Data;
}

const std::vector<int>& VideoRegistrationPipeline::frameOf() const
{
  return this->Impl->FrameOf;
}

double VideoRegistrationPipeline::framesPerSecond() const
{
  const Internals& d = *this->Impl;
  return framesPerSecondOf(d.RecordedFramesPerSecond, d.GivenFramesPerSecond);
}

std::vector<double> VideoRegistrationPipeline::frameTimesS() const
{
  const Internals& d = *this->Impl;
  std::vector<double> times;
  if (!d.TimesS.empty())
  {
    for (int loaded : d.FrameOf)
    {
      times.push_back(d.TimesS.at(static_cast<size_t>(loaded)));
    }
  }
  return times;
}

const std::vector<double>& VideoRegistrationPipeline::loadedFrameTimesS() const
{
  return this->Impl->TimesS;
}

const std::vector<SimilarityTransform>& VideoRegistrationPipeline::starts() const
{
  return this->Impl->Starts;
}

StartMode VideoRegistrationPipeline::startMode() const
{
  return this->Impl->Mode;
}

int VideoRegistrationPipeline::anchorFrameId() const
{
  return this->Impl->Anchor;
}

const MultiStartResult& VideoRegistrationPipeline::outcome() const
{
  return this->Impl->need(this->Impl->Outcome, "run the registration");
}

const RegistrationResult& VideoRegistrationPipeline::result() const
{
  return this->outcome().best;
}

bool VideoRegistrationPipeline::flaggedAsFailure() const
{
  return this->outcome().failure;
}

const StageTimings& VideoRegistrationPipeline::timings() const
{
  return this->Impl->Timings;
}

void VideoRegistrationPipeline::writeFrame(int index, const std::string& path) const
{
  const Internals& d = *this->Impl;
  if (index < 0 || index >= static_cast<int>(d.Frames.size()))
  {
    throw Error("video registration: no frame " + std::to_string(index));
  }
  if (!cv::imwrite(path, d.Frames[static_cast<size_t>(index)]))
  {
    throwFileError(path, "cannot write the frame");
  }
}

} // namespace vimlop
