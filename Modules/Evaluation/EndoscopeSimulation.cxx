#include <vimlop/Evaluation/EndoscopeSimulation.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/RandomDirection.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Evaluation/LensDistortionRendering.h>
#include <vimlop/Rendering/MucosaTexture.h>
#include <vimlop/Rendering/vtkVIMLOPVirtualEndoscope.h>
#include <vimlop/Video/IntrinsicsIO.h>

#include <vtkNew.h>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

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

bool EndoscopeSimulationOptions::isIdealWorld() const
{
  return !this->intrinsics.hasDistortion() && this->fieldStop.isOff() &&
    this->calibrationFocalErrorRelative == 0.0 && this->calibrationDistortionErrorRelative == 0.0 &&
    this->calibrationPrincipalPointErrorPx.isZero(0.0) && this->trackerLatencyS == 0.0 &&
    this->trackerClockOffsetS == 0.0 && this->trackerPositionBiasMm == 0.0 &&
    this->trackerRotationBiasDeg == 0.0 && this->artifacts.isOff() &&
    this->trajectory.jitterMm == 0.0 && this->trajectory.jitterDeg == 0.0;
}

void EndoscopeSimulationOptions::validate() const
{
  if (this->frames < 2)
  {
    throw Error("a simulated sequence needs at least 2 frames");
  }
  this->intrinsics.validate();
  this->fieldStop.validate();
  this->artifacts.validate();
  this->trajectory.validate();
  this->replay.validate();
  const Eigen::Index coefficients = this->intrinsics.distortion.size();
  // PinholeCamera::validate() above refuses a fisheye without its 4 and
  // counts OpenCV does not know; the simulated lens implements fewer.
  if (this->intrinsics.lensModel == LensModel::RadialTangential && coefficients != 0 &&
    coefficients != 4 && coefficients != 5 && coefficients != 8)
  {
    throw Error("the lens distortion needs 4, 5 or 8 coefficients (OpenCV's k1, k2, p1, p2[, k3[, "
                "k4, k5, k6]]), not " +
      std::to_string(coefficients));
  }
  if (!this->intrinsics.distortion.allFinite() ||
    (coefficients > 0 && this->intrinsics.distortion.cwiseAbs().maxCoeff() > 10.0))
  {
    throw Error("the lens distortion coefficients must be finite and within [-10, 10]");
  }
  if (!(std::abs(this->calibrationFocalErrorRelative) < 0.5))
  {
    throw Error("the calibration's relative focal error must lie in (-0.5, 0.5), not " +
      formatText("%g", this->calibrationFocalErrorRelative));
  }
  if (!(std::abs(this->calibrationDistortionErrorRelative) < 1.0))
  {
    throw Error("the calibration's relative distortion error must lie in (-1, 1), not " +
      formatText("%g", this->calibrationDistortionErrorRelative));
  }
  if (!this->calibrationPrincipalPointErrorPx.allFinite())
  {
    throw Error("the calibration's principal point error must be finite");
  }
  if (!(this->trackerRateHz > 0.0 && std::isfinite(this->trackerRateHz)))
  {
    throw Error("the tracker rate must be a finite number > 0 Hz");
  }
  if (!(this->trackerLatencyS >= 0.0 && std::isfinite(this->trackerLatencyS)))
  {
    throw Error("the tracker latency must be a finite number >= 0 s, not " +
      formatText("%g", this->trackerLatencyS));
  }
  if (!(this->trackerRotationNoiseDeg >= 0.0 && std::isfinite(this->trackerRotationNoiseDeg)))
  {
    throw Error("the tracker's rotation noise must be a finite number >= 0 degrees, not " +
      formatText("%g", this->trackerRotationNoiseDeg));
  }
  if (!(this->trackerPositionBiasMm >= 0.0 && std::isfinite(this->trackerPositionBiasMm)))
  {
    throw Error("the tracker's position bias must be a finite number >= 0 mm, not " +
      formatText("%g", this->trackerPositionBiasMm));
  }
  if (!(this->trackerRotationBiasDeg >= 0.0 && std::isfinite(this->trackerRotationBiasDeg)))
  {
    throw Error("the tracker's rotation bias must be a finite number >= 0 degrees, not " +
      formatText("%g", this->trackerRotationBiasDeg));
  }
  if (!std::isfinite(this->trackerClockOffsetS))
  {
    throw Error("the tracker's clock offset must be finite");
  }
}

namespace
{

/// The intrinsics a user is given: the true ones with the calibration error.
PinholeCamera calibratedIntrinsics(const EndoscopeSimulationOptions& o)
{
  PinholeCamera k = o.intrinsics;
  k.fx *= 1.0 + o.calibrationFocalErrorRelative;
  k.fy *= 1.0 + o.calibrationFocalErrorRelative;
  k.cx += o.calibrationPrincipalPointErrorPx.x();
  k.cy += o.calibrationPrincipalPointErrorPx.y();
  // Every coefficient alike, in either lens model: a calibration that
  // misjudges the lens's bending misjudges all of its terms.
  k.distortion *= 1.0 + o.calibrationDistortionErrorRelative;
  return k;
}

} // namespace

SimulatedVideo simulateEndoscopeVideo(const RegistrationModel& model,
  const EndoscopeSimulationOptions& o, const EvaluationProgress& progress)
{
  o.validate();
  EndoscopeTrajectoryOptions path = o.trajectory;
  path.frames = o.replay.isOff() ? o.frames : o.replay.pathFrames;
  path.intrinsics = o.intrinsics;
  SimulatedVideo video;
  video.intrinsics = o.intrinsics;
  video.calibratedIntrinsics = calibratedIntrinsics(o);
  video.camerasCT = makeEndoscopeTrajectory(model, path, o.seed);
  if (!o.replay.isOff())
  {
    video.camerasCT = replayPath(video.camerasCT, o.frames, o.replay, o.seed);
  }

  // The lens, the field stop and the artifacts of the light act on the
  // picture the optics form, before the sensor adds its noise; without them
  // the renderer's own noise is kept, so that the ideal world stays as it was.
  const VideoArtifactOptions& artifacts = o.artifacts;
  const bool distorted = o.intrinsics.hasDistortion();
  const bool optics = distorted || !o.fieldStop.isOff() || artifacts.actsOnLight();
  const std::vector<bool> occluded =
    occludedFrames(o.frames, artifacts.occludedFrameFraction, o.seed * 31337ull + 5ull);
  const std::vector<bool> touching = wallContactFrames(
    o.frames, artifacts.wallContactFraction, artifacts.wallContactFrames, o.seed * 7919ull + 17ull);
  PinholeCamera renderCamera = o.intrinsics;
  renderCamera.removeDistortion();
  cv::Mat lensMap;
  if (distorted)
  {
    renderCamera = pinholeCameraCovering(o.intrinsics);
    lensMap = distortedToPinholeMap(o.intrinsics, renderCamera);
  }
  cv::Mat gain; // per colour channel
  if (!o.fieldStop.isOff())
  {
    const cv::Mat grey = fieldStopGain(o.fieldStop, o.intrinsics.widthPx, o.intrinsics.heightPx);
    cv::merge(std::vector<cv::Mat>{ grey, grey, grey }, gain);
  }

  MucosaTextureOptions textureOptions;
  textureOptions.seed = o.seed;
  vtkNew<vtkVIMLOPVirtualEndoscope> endoscope;
  endoscope->SetBlurSigmaPx(o.blurSigmaPx);
  endoscope->SetNoiseSigma(optics ? 0.0 : o.noiseSigma);
  endoscope->SetMesh(model.mesh(), MucosaTexture(textureOptions));
  for (int f = 0; f < o.frames; ++f)
  {
    const std::uint64_t noiseSeed = o.seed * 100003ull + static_cast<std::uint64_t>(f);
    const EndoscopeImage image = endoscope->Render(renderCamera, video.camerasCT[f], noiseSeed);
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
    DepthMap depth = image.depth;
    // The light in floating point once an artifact acts before the lens;
    // empty until then, so that the lens alone samples the 8-bit picture as before.
    cv::Mat light;
    if (artifacts.exposureTimeS > 0.0 || artifacts.specularStrength > 0.0)
    {
      bgr.convertTo(light, CV_32FC3);
      if (artifacts.exposureTimeS > 0.0)
      {
        light = renderMotionBlur(light, image.depth, renderCamera, video.camerasCT[f],
          exposurePoses(video.camerasCT, f, o.framesPerSecond, artifacts.exposureTimeS,
            artifacts.motionBlurSamples));
      }
      if (artifacts.specularStrength > 0.0)
      {
        addSpecularHighlights(light,
          specularHighlights(
            image.depth, renderCamera, artifacts.specularStrength, artifacts.specularAngleDeg));
      }
    }
    if (distorted)
    {
      if (light.empty())
      {
        bgr = renderLensDistortion(bgr, lensMap);
      }
      else
      {
        light = renderLensDistortion(light, lensMap);
      }
      depth = renderLensDistortion(depth, lensMap);
    }
    if (optics)
    {
      if (light.empty())
      {
        bgr.convertTo(light, CV_32FC3);
      }
      if (touching[f])
      {
        applyWallContact(light);
      }
      if (occluded[f])
      {
        applyOccluders(light,
          occluderCoverage(light.cols, light.rows, artifacts.occluderAreaFraction,
            o.seed * 1000003ull + static_cast<std::uint64_t>(f)),
          artifacts.occluderOpacity);
      }
      // The field stop lies behind the lens window the fluid sits on: it
      // blackens the occluders too.
      if (!gain.empty())
      {
        light = light.mul(gain);
      }
      if (artifacts.actsOnLight())
      {
        // The sensor's well saturates (and nothing is darker than black)
        // before it reads out with its noise.
        applyExposure(light, artifacts.exposureGain);
      }
      bgr = addSensorNoise(light, o.noiseSigma, artifacts.shotNoise, noiseSeed);
    }
    video.frames.push_back(bgr);
    video.depth.push_back(depth);
    video.frameTimesS.push_back(f / o.framesPerSecond);
    reportEvaluationCount(progress, "simulate: frame", f + 1, o.frames);
  }

  // The recorder compresses what the sensor read out, the whole sequence at once.
  video.frames = compressVideo(
    video.frames, artifacts.compression, artifacts.compressionQuality, o.framesPerSecond);
  video.tracker = simulateTrackerRecording(video.camerasCT, o);
  return video;
}

TrackerTrajectory simulateTrackerRecording(
  const std::vector<CameraPose>& camerasCT, const EndoscopeSimulationOptions& o)
{
  if (camerasCT.size() < 2)
  {
    throw Error("a tracker recording needs at least 2 camera poses");
  }
  const int frames = static_cast<int>(camerasCT.size());
  std::mt19937_64 rng(o.seed * 7919ull + 17ull);
  std::normal_distribution<double> noise(0.0, o.trackerNoiseMm);
  // Drawn from a generator of its own, so that a position-only recording is
  // the same with the rotation on.
  std::mt19937_64 turnRng(o.seed * 7919ull + 29ull);
  std::normal_distribution<double> unitNoise(0.0, 1.0);
  // The navigation system's fixed error, from a generator of its own too.
  std::mt19937_64 biasRng(o.seed * 7919ull + 41ull);
  const Eigen::Vector3d positionBiasMm = o.trackerPositionBiasMm * randomDirection(biasRng);
  const Eigen::Matrix3d rotationBias =
    Eigen::AngleAxisd(o.trackerRotationBiasDeg * M_PI / 180.0, randomDirection(biasRng))
      .toRotationMatrix();
  std::vector<TrackerTrajectory::Sample> samples;
  const double start = -o.trackerMarginS;
  const double end = (frames - 1) / o.framesPerSecond + o.trackerMarginS;
  for (double t = start; t <= end + 1e-9; t += 1.0 / o.trackerRateHz)
  {
    // Where the tip was when the sample was measured: the stamp on the
    // tracker's clock, back to the video's, less the latency.
    const double seenS = t - o.trackerClockOffsetS - o.trackerLatencyS;
    const double frame = seenS * o.framesPerSecond;
    const int a = std::clamp(static_cast<int>(std::floor(frame)), 0, frames - 2);
    const double w = frame - a;
    const Eigen::Vector3d tip = (1.0 - w) * camerasCT[a].centre + w * camerasCT[a + 1].centre;
    samples.push_back(
      { t, tip + positionBiasMm + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)) });
    if (o.trackerRotation)
    {
      const double turn = std::clamp(w, 0.0, 1.0);
      const Eigen::Quaterniond q = Eigen::Quaterniond(camerasCT[a].rotation)
                                     .slerp(turn, Eigen::Quaterniond(camerasCT[a + 1].rotation));
      const Eigen::Vector3d errorDeg = o.trackerRotationNoiseDeg *
        Eigen::Vector3d(unitNoise(turnRng), unitNoise(turnRng), unitNoise(turnRng));
      samples.back().rotation =
        rotationFromVector(errorDeg * M_PI / 180.0) * rotationBias * q.toRotationMatrix();
    }
  }
  return TrackerTrajectory(samples);
}

void writeSimulatedVideo(const SimulatedVideo& video, const std::string& folder)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(fs::path(folder) / "frames", ec);
  fs::create_directories(fs::path(folder) / "truth" / "depth", ec);
  if (ec)
  {
    throwFileError(folder, "cannot create the folder (" + ec.message() + ")");
  }
  nlohmann::json frames = nlohmann::json::array();
  for (size_t f = 0; f < video.frames.size(); ++f)
  {
    const std::string framePath = (fs::path(folder) / "frames" / video.names[f]).string();
    if (!cv::imwrite(framePath, video.frames[f]))
    {
      throwFileError(framePath, "cannot write the image");
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
      (fs::path(folder) / "truth" / "depth" / fs::path(video.names[f]).replace_extension(".tiff"))
        .string();
    if (!cv::imwrite(depthPath, depth))
    {
      throwFileError(depthPath, "cannot write the depth map");
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
  writeIntrinsics(video.calibratedIntrinsics, (fs::path(folder) / "intrinsics.yaml").string());
  // The true intrinsics are truth, apart from what a user would have.
  fs::create_directories(fs::path(folder) / "truth", ec);
  if (ec)
  {
    throw Error("'" + folder + "/truth': cannot create the folder (" + ec.message() + ")");
  }
  writeIntrinsics(video.intrinsics, (fs::path(folder) / "truth" / "intrinsics.yaml").string());
  // The layout of FramePoseIO.h (with each frame's name and time), so that
  // every pose reader of VIMLOP reads it.
  const nlohmann::json poses = { { "frame", "CT (LPS, mm); camera x right, y down, z forward" },
    { "poses", frames } };
  const std::string posesPath = (fs::path(folder) / "truth" / "poses.json").string();
  std::ofstream out(posesPath);
  out << poses.dump(1) << "\n";
  if (!out)
  {
    throwFileError(posesPath, "cannot write the file");
  }
  video.tracker.writeCsv((fs::path(folder) / "tracker.csv").string());
}

} // namespace vimlop
