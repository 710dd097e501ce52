#include <vimlop/Video/SfmReconstructor.h>

#include <vimlop/Video/BundleAdjustment.h>

#include <algorithm>
#include <cmath>
#include <ostream>

namespace vimlop::detail
{

SfmReconstructor::SfmReconstructor(const StructureFromMotionOptions& options,
  const std::vector<cv::Mat>& frames, const PinholeCamera& k, std::ostream* log,
  const cv::Mat& featureMask)
  : O(options)
  , Frames(frames)
  , FeatureMask(featureMask)
  , K(k)
  , Log(log)
{
}

SfmReconstruction SfmReconstructor::run(const std::vector<std::string>& names)
{
  this->detect();
  this->match();
  this->buildTracks();
  this->initialise();
  this->registerRemaining();
  return this->result(names);
}

void SfmReconstructor::say(const std::string& text)
{
  if (this->Log)
  {
    *this->Log << "sfm: " << text << "\n";
  }
}

void SfmReconstructor::adjust(int iterations)
{
  std::vector<int> cameraOf(this->Frames.size(), -1);
  std::vector<CameraPose> cameras;
  std::vector<PinholeCamera> intrinsics;
  for (size_t f = 0; f < this->Frames.size(); ++f)
  {
    if (this->Registered[f])
    {
      cameraOf[f] = static_cast<int>(cameras.size());
      cameras.push_back(this->Poses[f]);
      intrinsics.push_back(this->K);
    }
  }
  std::vector<BundleAdjustment::Observation> observations;
  for (size_t p = 0; p < this->Points.size(); ++p)
  {
    for (const auto& [frame, pixel] : this->Observations[p])
    {
      observations.push_back({ cameraOf[frame], static_cast<int>(p), pixel });
    }
  }
  BundleAdjustmentOptions options;
  options.maxIterations = iterations;
  options.scaleCamera = cameraOf[this->ScaleCamera];
  BundleAdjustment::adjust(
    cameras, this->Points, intrinsics, observations, { cameraOf[this->Origin] }, options);
  for (size_t f = 0; f < this->Frames.size(); ++f)
  {
    if (cameraOf[f] >= 0)
    {
      this->Poses[f] = cameras[cameraOf[f]];
    }
  }
  // Remove observations that the adjusted geometry does not explain.
  for (size_t p = 0; p < this->Points.size(); ++p)
  {
    auto& seen = this->Observations[p];
    seen.erase(std::remove_if(seen.begin(), seen.end(),
                 [&](const std::pair<int, Eigen::Vector2d>& o)
                 {
                   const Eigen::Vector3d c = this->Poses[o.first].worldToCamera(this->Points[p]);
                   return c.z() <= 0.0 ||
                     (this->K.project(c) - o.second).norm() > this->O.maxReprojectionErrorPx;
                 }),
      seen.end());
  }
}

SfmReconstruction SfmReconstructor::result(const std::vector<std::string>& names)
{
  SfmReconstruction r;
  r.source = "builtin";
  // One SfM unit: the mean distance between consecutive registered cameras.
  double path = 0.0;
  int steps = 0;
  int previous = -1;
  for (size_t f = 0; f < this->Frames.size(); ++f)
  {
    if (this->Registered[f])
    {
      if (previous >= 0)
      {
        path += (this->Poses[f].centre - this->Poses[previous].centre).norm();
        ++steps;
      }
      previous = static_cast<int>(f);
    }
  }
  const double scale = steps > 0 && path > 0.0 ? steps / path : 1.0;
  for (size_t f = 0; f < this->Frames.size(); ++f)
  {
    SfmReconstruction::Frame frame;
    frame.name = f < names.size() ? names[f] : "frame" + std::to_string(f);
    frame.registered = this->Registered[f];
    frame.intrinsics = this->K;
    if (frame.registered)
    {
      frame.cameraToSfm = this->Poses[f];
      frame.cameraToSfm.centre *= scale;
    }
    r.frames.push_back(frame);
  }
  for (size_t p = 0; p < this->Points.size(); ++p)
  {
    const auto& seen = this->Observations[p];
    if (static_cast<int>(seen.size()) < this->O.minTrackLength)
    {
      continue;
    }
    SfmReconstruction::Point point;
    point.position = scale * this->Points[p];
    for (const auto& [frame, pixel] : seen)
    {
      point.observations.push_back({ frame, pixel });
    }
    const cv::Mat& image = this->Frames[seen.front().first];
    const int u =
      std::clamp(static_cast<int>(std::lround(seen.front().second.x())), 0, image.cols - 1);
    const int v =
      std::clamp(static_cast<int>(std::lround(seen.front().second.y())), 0, image.rows - 1);
    if (image.channels() == 3)
    {
      const cv::Vec3b bgr = image.at<cv::Vec3b>(v, u);
      point.colour = Eigen::Vector3i(bgr[2], bgr[1], bgr[0]);
    }
    else
    {
      const int g = image.at<unsigned char>(v, u);
      point.colour = Eigen::Vector3i(g, g, g);
    }
    r.points.push_back(std::move(point));
  }
  const double rms = std::max(0.1, r.rmsReprojectionErrorPx());
  r.computeCovariances(rms);
  int unregistered = 0;
  for (const SfmReconstruction::Frame& f : r.frames)
  {
    unregistered += !f.registered;
  }
  this->say(std::to_string(r.numberOfRegisteredFrames()) + " of " +
    std::to_string(r.frames.size()) + " frames registered" +
    (unregistered ? " (the others are dropped)" : "") + ", " + std::to_string(r.points.size()) +
    " points, RMS reprojection error " + std::to_string(r.rmsReprojectionErrorPx()) + " px");
  return r;
}

} // namespace vimlop::detail
