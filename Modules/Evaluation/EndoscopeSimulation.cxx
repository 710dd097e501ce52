#include <vimlop/Evaluation/EndoscopeSimulation.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Rendering/MucosaTexture.h>
#include <vimlop/Rendering/vtkVIMLOPVirtualEndoscope.h>
#include <vimlop/Video/IntrinsicsIO.h>

#include <vtkNew.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

namespace vimlop
{

double SimulatedVideo::pathLengthMm() const
{
  double length = 0.0;
  for (size_t f = 1; f < this->camerasCT.size(); ++f)
  {
    length += (this->camerasCT[f].centre - this->camerasCT[f - 1].centre).norm();
  }
  return length;
}

double SimulatedVideo::leastWallDistanceMm(const RegistrationModel& model) const
{
  double distance = std::numeric_limits<double>::infinity();
  for (const CameraPose& camera : this->camerasCT)
  {
    distance = std::min(distance, model.locator().closestPoint(camera.centre).distanceMm);
  }
  return distance;
}

SimulatedVideo simulateEndoscopeVideo(const RegistrationModel& model,
  const EndoscopeSimulationOptions& o, const EvaluationProgress& progress)
{
  if (o.frames < 2)
  {
    throw Error("a simulated sequence needs at least 2 frames");
  }
  o.intrinsics.validate();
  EndoscopeTrajectoryOptions path = o.trajectory;
  path.frames = o.frames;
  path.intrinsics = o.intrinsics;
  SimulatedVideo video;
  video.intrinsics = o.intrinsics;
  video.camerasCT = makeEndoscopeTrajectory(model, path, o.seed);

  MucosaTextureOptions textureOptions;
  textureOptions.seed = o.seed;
  vtkNew<vtkVIMLOPVirtualEndoscope> endoscope;
  endoscope->SetBlurSigmaPx(o.blurSigmaPx);
  endoscope->SetNoiseSigma(o.noiseSigma);
  endoscope->SetMesh(model.mesh(), MucosaTexture(textureOptions));
  for (int f = 0; f < o.frames; ++f)
  {
    const EndoscopeImage image = endoscope->Render(
      o.intrinsics, video.camerasCT[f], o.seed * 100003ull + static_cast<std::uint64_t>(f));
    cv::Mat bgr(image.heightPx, image.widthPx, CV_8UC3);
    for (int v = 0; v < image.heightPx; ++v)
    {
      for (int u = 0; u < image.widthPx; ++u)
      {
        bgr.at<cv::Vec3b>(v, u) =
          cv::Vec3b(image.channel(u, v, 2), image.channel(u, v, 1), image.channel(u, v, 0));
      }
    }
    char name[32];
    std::snprintf(name, sizeof(name), "frame%03d.png", f);
    video.names.emplace_back(name);
    video.frames.push_back(bgr);
    video.depth.push_back(image.depth);
    video.frameTimesS.push_back(f / o.framesPerSecond);
    reportEvaluationCount(progress, "simulate: frame", f + 1, o.frames);
  }

  // The tracker follows the tip (linear between frames, extrapolated at
  // constant velocity before the first and after the last) with Gaussian noise.
  std::mt19937_64 rng(o.seed * 7919ull + 17ull);
  std::normal_distribution<double> noise(0.0, o.trackerNoiseMm);
  std::vector<TrackerTrajectory::Sample> samples;
  const double start = -o.trackerMarginS;
  const double end = video.frameTimesS.back() + o.trackerMarginS;
  for (double t = start; t <= end + 1e-9; t += 1.0 / o.trackerRateHz)
  {
    const double frame = t * o.framesPerSecond;
    const int a = std::clamp(static_cast<int>(std::floor(frame)), 0, o.frames - 2);
    const double w = frame - a;
    const Eigen::Vector3d tip =
      (1.0 - w) * video.camerasCT[a].centre + w * video.camerasCT[a + 1].centre;
    samples.push_back({ t, tip + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)) });
  }
  video.tracker = TrackerTrajectory(samples);
  return video;
}

void writeSimulatedVideo(const SimulatedVideo& video, const std::string& folder)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(fs::path(folder) / "frames", ec);
  fs::create_directories(fs::path(folder) / "depth", ec);
  if (ec)
  {
    throw Error("'" + folder + "': cannot create the folder (" + ec.message() + ")");
  }
  nlohmann::json frames = nlohmann::json::array();
  for (size_t f = 0; f < video.frames.size(); ++f)
  {
    const std::string framePath = (fs::path(folder) / "frames" / video.names[f]).string();
    if (!cv::imwrite(framePath, video.frames[f]))
    {
      throw Error("'" + framePath + "': cannot write the image");
    }
    const DepthMap& d = video.depth[f];
    cv::Mat depth(d.heightPx, d.widthPx, CV_32F);
    for (int v = 0; v < d.heightPx; ++v)
    {
      for (int u = 0; u < d.widthPx; ++u)
      {
        const float z = d.at(u, v);
        depth.at<float>(v, u) = std::isfinite(z) ? z : 0.0f;
      }
    }
    const std::string depthPath =
      (fs::path(folder) / "depth" / fs::path(video.names[f]).replace_extension(".tiff")).string();
    if (!cv::imwrite(depthPath, depth))
    {
      throw Error("'" + depthPath + "': cannot write the depth map");
    }
    const Eigen::Matrix4d m = video.camerasCT[f].matrix();
    std::vector<double> rows;
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        rows.push_back(m(r, c));
      }
    }
    frames.push_back({ { "frame_id", f }, { "name", video.names[f] },
      { "time_s", video.frameTimesS[f] }, { "camera_to_ct", rows } });
  }
  writeIntrinsics(video.intrinsics, (fs::path(folder) / "intrinsics.yaml").string());
  // The layout of FramePoseIO.h (with each frame's name and time), so that
  // every pose reader of VIMLOP reads it.
  const nlohmann::json poses = { { "frame", "CT (LPS, mm); camera x right, y down, z forward" },
    { "poses", frames } };
  const std::string posesPath = (fs::path(folder) / "poses.json").string();
  std::ofstream out(posesPath);
  out << poses.dump(1) << "\n";
  if (!out)
  {
    throw Error("'" + posesPath + "': cannot write the file");
  }
  video.tracker.writeCsv((fs::path(folder) / "tracker.csv").string());
}

} // namespace vimlop
