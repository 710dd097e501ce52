#include <vimlop/Evaluation/VideoArtifacts.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace vimlop
{

std::string videoCompressionName(VideoCompression codec)
{
  switch (codec)
  {
    case VideoCompression::None:
      return "none";
    case VideoCompression::Mjpg:
      return "mjpg";
    case VideoCompression::H264:
      return "h264";
    case VideoCompression::Mp4v:
      return "mp4v";
  }
  return "unknown";
}

void VideoArtifactOptions::validate() const
{
  // `!(inside)` rather than `outside` so that NaN is refused too.
  auto inRange = [](double value, double low, double high, bool lowOpen)
  { return (lowOpen ? value > low : value >= low) && value <= high; };
  if (!inRange(this->exposureTimeS, 0.0, 1.0, false))
  {
    throw Error(
      "the exposure time must lie in [0, 1] s, not " + formatText("%g", this->exposureTimeS));
  }
  if (this->motionBlurSamples < 2 || this->motionBlurSamples > 64)
  {
    throw Error("the motion blur's number of samples must lie in [2, 64], not " +
      std::to_string(this->motionBlurSamples));
  }
  if (!inRange(this->specularStrength, 0.0, 10.0, false))
  {
    throw Error("the specular highlights' strength must lie in [0, 10], not " +
      formatText("%g", this->specularStrength));
  }
  if (!inRange(this->specularAngleDeg, 0.0, 45.0, true))
  {
    throw Error("the specular highlights' angle must lie in (0, 45] degrees, not " +
      formatText("%g", this->specularAngleDeg));
  }
  if (!inRange(this->exposureGain, 0.0, 10.0, true))
  {
    throw Error(
      "the exposure gain must lie in (0, 10], not " + formatText("%g", this->exposureGain));
  }
  if (!inRange(this->shotNoise, 0.0, 10.0, false))
  {
    throw Error("the shot noise must lie in [0, 10] grey levels per electron, not " +
      formatText("%g", this->shotNoise));
  }
  if (videoCompressionName(this->compression) == "unknown")
  {
    throw Error("unknown video compression " + std::to_string(static_cast<int>(this->compression)));
  }
  if (this->compressionQuality < 0 || this->compressionQuality > 100)
  {
    throw Error("the compression quality must lie in [1, 100] (0: the writer's own), not " +
      std::to_string(this->compressionQuality));
  }
  if (this->compressionQuality != 0 && this->compression != VideoCompression::Mjpg &&
    this->compression != VideoCompression::None)
  {
    throw Error("the compression quality applies to mjpg only: OpenCV's FFmpeg writer of " +
      videoCompressionName(this->compression) + " has no quality setting");
  }
  if (!inRange(this->occludedFrameFraction, 0.0, 1.0, false))
  {
    throw Error("the fraction of occluded frames must lie in [0, 1], not " +
      formatText("%g", this->occludedFrameFraction));
  }
  if (!inRange(this->occluderAreaFraction, 0.0, 0.9, true))
  {
    throw Error("the occluders' area fraction must lie in (0, 0.9], not " +
      formatText("%g", this->occluderAreaFraction));
  }
  if (!inRange(this->occluderOpacity, 0.0, 1.0, true))
  {
    throw Error(
      "the occluders' opacity must lie in (0, 1], not " + formatText("%g", this->occluderOpacity));
  }
  if (!inRange(this->wallContactFraction, 0.0, 0.5, false))
  {
    throw Error("the fraction of frames in wall contact must lie in [0, 0.5], not " +
      formatText("%g", this->wallContactFraction));
  }
  if (this->wallContactFrames < 1 || this->wallContactFrames > 300)
  {
    throw Error("a stretch of wall contact must last 1 to 300 frames, not " +
      std::to_string(this->wallContactFrames));
  }
}

std::vector<CameraPose> exposurePoses(const std::vector<CameraPose>& cameras, int frame,
  double framesPerSecond, double exposureTimeS, int samples)
{
  if (cameras.size() < 2 || frame < 0 || frame >= static_cast<int>(cameras.size()) || samples < 2 ||
    !(framesPerSecond > 0.0))
  {
    throw Error("exposure poses need 2 or more cameras, a frame among them, 2 or more samples and "
                "a frame rate > 0");
  }
  const int last = static_cast<int>(cameras.size()) - 1;
  std::vector<CameraPose> poses;
  for (int s = 0; s < samples; ++s)
  {
    const double t = exposureTimeS * (static_cast<double>(s) / (samples - 1) - 0.5);
    const double at = frame + t * framesPerSecond;
    const int a = std::clamp(static_cast<int>(std::floor(at)), 0, last - 1);
    // w outside [0, 1] beyond the ends: the first or last step's velocity goes on.
    const double w = at - a;
    const CameraPose& p = cameras[a];
    const CameraPose& q = cameras[a + 1];
    // The step's rotation as an angle about an axis, scaled: spherical-linear
    // within the step and a constant angular velocity beyond it.
    const Eigen::AngleAxisd step(p.rotation.transpose() * q.rotation);
    CameraPose pose;
    pose.rotation =
      p.rotation * Eigen::AngleAxisd(w * step.angle(), step.axis()).toRotationMatrix();
    pose.centre = (1.0 - w) * p.centre + w * q.centre;
    poses.push_back(pose);
  }
  return poses;
}

namespace
{

bool hasSurface(float z)
{
  // The renderer marks no surface with +infinity, the depth files with 0.
  return std::isfinite(z) && z > 0.0f;
}

} // namespace

cv::Mat renderMotionBlur(const cv::Mat& picture, const DepthMap& depth, const PinholeCamera& camera,
  const CameraPose& framePose, const std::vector<CameraPose>& poses)
{
  const int w = picture.cols;
  const int h = picture.rows;
  if (depth.widthPx != w || depth.heightPx != h)
  {
    throw Error("the motion blur's depth map (" + std::to_string(depth.widthPx) + " x " +
      std::to_string(depth.heightPx) + ") does not match the picture (" + std::to_string(w) +
      " x " + std::to_string(h) + ")");
  }
  const bool moves = std::any_of(poses.begin(), poses.end(),
    [&framePose](const CameraPose& p)
    { return p.rotation != framePose.rotation || p.centre != framePose.centre; });
  if (!moves)
  {
    return picture.clone();
  }
  // Per sample, each pixel's displacement: where the surface point it sees
  // at the frame's pose is seen from the sample's pose.
  const int n = static_cast<int>(poses.size());
  std::vector<cv::Mat> flow(n);
  for (cv::Mat& m : flow)
  {
    m = cv::Mat(h, w, CV_32FC2, cv::Scalar::all(0.0));
  }
  cv::Mat noSurface(h, w, CV_8U, cv::Scalar(0));
  int surfacePixels = 0;
  double longestFlowPx = 0.0;
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      const float z = depth.at(u, v);
      if (!hasSurface(z))
      {
        noSurface.at<std::uint8_t>(v, u) = 1;
        continue;
      }
      ++surfacePixels;
      const Eigen::Vector3d world =
        framePose.cameraToWorld(camera.backProject(Eigen::Vector2d(u, v), z));
      for (int s = 0; s < n; ++s)
      {
        const Eigen::Vector3d c = poses[s].worldToCamera(world);
        // A point that passes behind the camera during the exposure has no
        // image: it stays where it is rather than sampling infinity.
        const Eigen::Vector2d p = c.z() > 1e-6 ? camera.project(c) : Eigen::Vector2d(u, v);
        longestFlowPx = std::max(longestFlowPx, std::hypot(p.x() - u, p.y() - v));
        flow[s].at<cv::Vec2f>(v, u) =
          cv::Vec2f(static_cast<float>(p.x() - u), static_cast<float>(p.y() - v));
      }
    }
  }
  // Rounding in the poses' interpolation moves a still camera by far less
  // than this; averaging would then change the picture by rounding alone.
  if (surfacePixels == 0 || longestFlowPx < 1e-4)
  {
    return picture.clone();
  }
  if (surfacePixels < w * h)
  {
    // Pixels without a surface (the view down the airway) move with their
    // nearest neighbour that has one: the camera's motion blurs them alike.
    cv::Mat distance;
    cv::Mat labels;
    cv::distanceTransform(
      noSurface, distance, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
    std::vector<int> source(static_cast<size_t>(w) * h + 1, -1);
    for (int v = 0; v < h; ++v)
    {
      for (int u = 0; u < w; ++u)
      {
        if (!noSurface.at<std::uint8_t>(v, u))
        {
          source[labels.at<int>(v, u)] = v * w + u;
        }
      }
    }
    for (int v = 0; v < h; ++v)
    {
      for (int u = 0; u < w; ++u)
      {
        const int from = noSurface.at<std::uint8_t>(v, u) ? source[labels.at<int>(v, u)] : -1;
        if (from < 0)
        {
          continue;
        }
        for (cv::Mat& m : flow)
        {
          m.at<cv::Vec2f>(v, u) = m.at<cv::Vec2f>(from / w, from % w);
        }
      }
    }
  }
  cv::Mat light;
  picture.convertTo(light, CV_32F);
  cv::Mat sum(h, w, light.type(), cv::Scalar::all(0.0));
  for (cv::Mat& m : flow)
  {
    for (int v = 0; v < h; ++v)
    {
      for (int u = 0; u < w; ++u)
      {
        m.at<cv::Vec2f>(v, u) += cv::Vec2f(static_cast<float>(u), static_cast<float>(v));
      }
    }
    cv::Mat sampled;
    cv::remap(light, sampled, m, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    sum += sampled;
  }
  sum /= static_cast<double>(n);
  cv::Mat blurred;
  sum.convertTo(blurred, picture.type());
  return blurred;
}

cv::Mat specularHighlights(
  const DepthMap& depth, const PinholeCamera& camera, double strength, double angleDeg)
{
  const int w = depth.widthPx;
  const int h = depth.heightPx;
  cv::Mat highlights(h, w, CV_32F, cv::Scalar(0.0f));
  if (strength <= 0.0)
  {
    return highlights;
  }
  const double limit = angleDeg * M_PI / 180.0;
  // The airway is a triangle mesh, the mucosa is smooth: normals of the raw
  // depth would be the facets', each lit whole or not at all. The inverse
  // depth is smoothed over the pixels with a surface only (normalised
  // convolution; a plane's inverse depth is affine in the pixel, so that
  // planes stay planes), and the normals are taken over a baseline of a few
  // pixels.
  cv::Mat inverse(h, w, CV_32F, cv::Scalar(0.0f));
  cv::Mat seen(h, w, CV_32F, cv::Scalar(0.0f));
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      if (hasSurface(depth.at(u, v)))
      {
        inverse.at<float>(v, u) = 1.0f / depth.at(u, v);
        seen.at<float>(v, u) = 1.0f;
      }
    }
  }
  const double smoothingPx = 3.0;
  const int baselinePx = 2;
  // Beyond the image is no surface either: a reflected border would bend planes there.
  cv::GaussianBlur(inverse, inverse, cv::Size(0, 0), smoothingPx, 0.0, cv::BORDER_CONSTANT);
  cv::GaussianBlur(seen, seen, cv::Size(0, 0), smoothingPx, 0.0, cv::BORDER_CONSTANT);
  auto point = [&](int u, int v, Eigen::Vector3d& x)
  {
    // Near the edge of what has a surface (and of the image), the smoothing
    // would mix in the void: about 7 px.
    const float support = seen.at<float>(v, u);
    if (!hasSurface(depth.at(u, v)) || support < 0.99f)
    {
      return false;
    }
    x = camera.backProject(Eigen::Vector2d(u, v), support / inverse.at<float>(v, u));
    return true;
  };
  const int b = baselinePx;
  for (int v = b; v + b < h; ++v)
  {
    for (int u = b; u + b < w; ++u)
    {
      Eigen::Vector3d x, left, right, up, down;
      if (!point(u, v, x) || !point(u - b, v, left) || !point(u + b, v, right) ||
        !point(u, v - b, up) || !point(u, v + b, down))
      {
        continue;
      }
      const Eigen::Vector3d normal = (right - left).cross(down - up);
      if (normal.norm() == 0.0)
      {
        continue;
      }
      // Light and lens at the same point: the mirror direction is back along
      // the ray, so the highlight is where the normal is the ray's reverse.
      // Which side the normal points to does not matter: the side seen faces the camera.
      const double facing = std::abs(normal.normalized().dot(x.normalized()));
      const double angle = std::acos(std::min(facing, 1.0));
      if (angle < limit)
      {
        highlights.at<float>(v, u) =
          static_cast<float>(strength * (1.0 - (angle / limit) * (angle / limit)));
      }
    }
  }
  return highlights;
}

void addSpecularHighlights(cv::Mat& light, const cv::Mat& highlights)
{
  // The mirrored light is the lamp's white, not the tissue's colour.
  cv::Mat white;
  cv::merge(std::vector<cv::Mat>{ highlights, highlights, highlights }, white);
  light += white * 255.0;
}

void applyExposure(cv::Mat& light, double gain)
{
  light *= gain;
  cv::min(light, 255.0, light);
  cv::max(light, 0.0, light);
}

cv::Mat addSensorNoise(const cv::Mat& light, double sigma, double shotNoise, std::uint64_t seed)
{
  // The seed and the order of draws are those the simulator had before the
  // shot noise, so that the sequences without it stay as they were.
  std::mt19937_64 rng(seed * 0x2545f4914f6cdd1dull + 977u);
  std::normal_distribution<double> noise(0.0, 1.0);
  cv::Mat out(light.rows, light.cols, CV_8UC3);
  for (int v = 0; v < light.rows; ++v)
  {
    for (int u = 0; u < light.cols; ++u)
    {
      const cv::Vec3f in = light.at<cv::Vec3f>(v, u);
      cv::Vec3b& pixel = out.at<cv::Vec3b>(v, u);
      for (int c = 0; c < 3; ++c)
      {
        const double sd = shotNoise > 0.0
          ? std::sqrt(sigma * sigma + shotNoise * std::max(0.0, static_cast<double>(in[c])))
          : sigma;
        const double value = in[c] + (sd > 0.0 ? sd * noise(rng) : 0.0);
        pixel[c] = static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L));
      }
    }
  }
  return out;
}

std::vector<cv::Mat> compressVideo(
  const std::vector<cv::Mat>& frames, VideoCompression codec, int quality, double framesPerSecond)
{
  if (codec == VideoCompression::None || frames.empty())
  {
    return frames;
  }
  const std::string name = videoCompressionName(codec);
  const cv::Size size = frames.front().size();
  for (const cv::Mat& frame : frames)
  {
    if (frame.type() != CV_8UC3 || frame.size() != size)
    {
      throw Error("video compression needs 8-bit colour frames all of one size");
    }
  }
  namespace fs = std::filesystem;
  static std::atomic<unsigned> serial{ 0 };
  const bool mjpg = codec == VideoCompression::Mjpg;
  const fs::path path = fs::temp_directory_path() /
    ("vimlop-compression-" + std::to_string(::getpid()) + "-" + std::to_string(serial++) +
      (mjpg ? ".avi" : ".mp4"));
  // The temporary file goes whatever happens.
  struct Removal
  {
    fs::path path;
    ~Removal()
    {
      std::error_code ec;
      fs::remove(this->path, ec);
    }
  } removal{ path };
  // OpenCV 4.6's FFmpeg writer ignores a quality, its own MJPEG writer takes one.
  const int api = mjpg ? cv::CAP_OPENCV_MJPEG : cv::CAP_FFMPEG;
  const int fourcc = mjpg             ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G')
    : codec == VideoCompression::H264 ? cv::VideoWriter::fourcc('a', 'v', 'c', '1')
                                      : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
  cv::VideoWriter writer;
  if (!writer.open(path.string(), api, fourcc, framesPerSecond, size, true))
  {
    throw Error("the video codec " + name +
      " is not available: OpenCV's VideoWriter cannot write " +
      (mjpg ? "Motion JPEG .avi" : "it to .mp4 (FFmpeg backend)") + " on this system");
  }
  if (quality > 0 && !writer.set(cv::VIDEOWRITER_PROP_QUALITY, quality))
  {
    throw Error("the " + name + " writer does not take a quality");
  }
  for (const cv::Mat& frame : frames)
  {
    writer.write(frame);
  }
  writer.release();
  cv::VideoCapture capture(path.string(), cv::CAP_FFMPEG);
  if (!capture.isOpened())
  {
    throwFileError(path.string(), "cannot read back the " + name + " video");
  }
  std::vector<cv::Mat> decoded;
  cv::Mat frame;
  while (capture.read(frame))
  {
    decoded.push_back(frame.clone());
  }
  if (decoded.size() != frames.size() || decoded.front().size() != size)
  {
    throw Error("the " + name + " video read back has " + std::to_string(decoded.size()) +
      " frames, not " + std::to_string(frames.size()));
  }
  return decoded;
}

} // namespace vimlop
