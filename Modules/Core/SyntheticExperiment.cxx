#include <vimlop/Core/SyntheticExperiment.h>

#include <vimlop/Core/AnatomicalConstraint.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/NoiseModel.h>
#include <vimlop/Core/RayClearance.h>
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Core/VisibleModelContours.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>

namespace vimlop
{

namespace
{

constexpr double Degree = M_PI / 180.0;

class Sampler
{
public:
  explicit Sampler(std::uint64_t seed)
    : Engine(seed)
  {
  }
  double uniform(double lo, double hi)
  {
    return std::uniform_real_distribution<double>(lo, hi)(this->Engine);
  }
  double normal() { return this->Normal(this->Engine); }
  Eigen::Vector3d direction()
  {
    Eigen::Vector3d v;
    do
    {
      v = Eigen::Vector3d(this->normal(), this->normal(), this->normal());
    } while (v.norm() < 1e-9);
    return v.normalized();
  }
  int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(this->Engine); }

private:
  std::mt19937_64 Engine;
  std::normal_distribution<double> Normal;
};

/// Points `pointsCT` that `camera` sees: in front, inside the image, unoccluded.
std::vector<char> seenBy(const RegistrationModel& model, const PinholeCamera& k,
  const CameraPose& camera, const std::vector<Eigen::Vector3d>& pointsCT)
{
  std::vector<char> visible;
  model.visibility().classify(k, camera, pointsCT, visible);
  for (size_t i = 0; i < pointsCT.size(); ++i)
  {
    const Eigen::Vector3d p = camera.worldToCamera(pointsCT[i]);
    if (p.z() < 0.5 || !k.isInImage(k.project(p)))
    {
      visible[i] = 0;
    }
  }
  return visible;
}

/// True when `centre` is inside `model` at least `clearanceMm` from its wall.
bool hasClearance(const RegistrationModel& model, const Eigen::Vector3d& centre, double clearanceMm)
{
  return model.isInside(centre) && model.locator().closestPoint(centre).distanceMm >= clearanceMm;
}

/// A camera path in the anatomy `model`; with `alsoInside`, the cameras keep
/// their clearance in it too (the registration's model, when the data come
/// from another surface: V-IMLOP's anatomical constraint needs the true
/// cameras inside the model).
std::vector<CameraPose> cameraPath(const RegistrationModel& model, const SyntheticOptions& o,
  Sampler& rng, const RegistrationModel* alsoInside)
{
  const Eigen::Matrix<double, 3, 2> bounds = model.mesh().bounds();
  const double pathLength = (o.cameras - 1) * o.cameraStepMm;
  for (int attempt = 0; attempt < 5000; ++attempt)
  {
    const Eigen::Vector3d start(rng.uniform(bounds(0, 0), bounds(0, 1)),
      rng.uniform(bounds(1, 0), bounds(1, 1)), rng.uniform(bounds(2, 0), bounds(2, 1)));
    if (!model.isInside(start) || model.locator().closestPoint(start).distanceMm < o.minClearanceMm)
    {
      continue;
    }
    // Look along the longest free direction among a few: along the passage.
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    double bestFree = 0.0;
    for (int k = 0; k < 32; ++k)
    {
      const Eigen::Vector3d d = rng.direction();
      // 1 mm steps: the path needs 5 mm more than its length, far coarser.
      const double free = freeLengthAlongRay(model.tree(), start, d, 40.0, 1.0);
      if (free > bestFree)
      {
        bestFree = free;
        best = d;
      }
    }
    if (bestFree < pathLength + 5.0)
    {
      continue;
    }
    Eigen::Vector3d up = rng.direction();
    up -= up.dot(best) * best;
    if (up.norm() < 1e-3)
    {
      continue;
    }
    std::vector<CameraPose> path;
    bool ok = true;
    for (int c = 0; c < o.cameras && ok; ++c)
    {
      const Eigen::Vector3d centre = start + c * o.cameraStepMm * best;
      ok = hasClearance(model, centre, o.minClearanceMm) &&
        (alsoInside == nullptr || hasClearance(*alsoInside, centre, o.minClearanceMm));
      // Each view turns by up to 10° from the path, as a hand-held endoscope does.
      const Eigen::Vector3d look =
        rotationFromVector(10.0 * Degree * rng.uniform(0.0, 1.0) * rng.direction()) * best;
      path.push_back(CameraPose::lookAt(centre, centre + look, up));
    }
    if (ok)
    {
      return path;
    }
  }
  throw Error("synthetic experiment: found no camera path inside the model with " +
    std::to_string(o.minClearanceMm) + " mm clearance");
}

Eigen::Vector3d randomPointOnFace(const TriangleMesh& mesh, int face, Sampler& rng)
{
  // Uniform on the triangle: reflect the unit square's upper half.
  double u = rng.uniform(0.0, 1.0);
  double v = rng.uniform(0.0, 1.0);
  if (u + v > 1.0)
  {
    u = 1.0 - u;
    v = 1.0 - v;
  }
  return mesh.corner(face, 0) + u * (mesh.corner(face, 1) - mesh.corner(face, 0)) +
    v * (mesh.corner(face, 2) - mesh.corner(face, 0));
}

} // namespace

SyntheticTrial makeSyntheticTrial(
  const RegistrationModel& model, const SyntheticOptions& o, std::uint64_t seed)
{
  return makeSyntheticTrial(model, model, o, seed);
}

SyntheticTrial makeSyntheticTrial(const RegistrationModel& model,
  const RegistrationModel& dataSurface, const SyntheticOptions& o, std::uint64_t seed)
{
  if (o.cameras < 1 || o.points < 3)
  {
    throw Error("synthetic experiment: needs at least 1 camera and 3 points");
  }
  if (!(o.contourNoisePx >= 0.0) || !(o.contourNormalKappa >= 0.0))
  {
    throw Error("synthetic experiment: the contour noise and its kappa must not be negative");
  }
  if (!(o.startScaleError > -1.0 && std::isfinite(o.startScaleError)))
  {
    throw Error("synthetic experiment: the start's scale error must be a finite number above -1, "
                "not " +
      formatText("%g", o.startScaleError));
  }
  o.intrinsics.validate();
  Sampler rng(seed);
  // The targets are the model's faces; the points are drawn from the data's.
  const TriangleMesh& mesh = model.mesh();
  const TriangleMesh& dataMesh = dataSurface.mesh();
  std::vector<double> cumulativeArea(static_cast<size_t>(dataMesh.numberOfFaces()));
  double area = 0.0;
  for (int f = 0; f < dataMesh.numberOfFaces(); ++f)
  {
    area += dataMesh.faceAreas()[f];
    cumulativeArea[f] = area;
  }

  for (int attempt = 0; attempt < 50; ++attempt)
  {
    SyntheticTrial trial;
    trial.trueCamerasCT =
      cameraPath(dataSurface, o, rng, &dataSurface == &model ? nullptr : &model);

    // Targets: faces visible to the middle camera.
    const CameraPose& middle = trial.trueCamerasCT[trial.trueCamerasCT.size() / 2];
    std::vector<Eigen::Vector3d> centroids(static_cast<size_t>(mesh.numberOfFaces()));
    for (int f = 0; f < mesh.numberOfFaces(); ++f)
    {
      centroids[f] = mesh.faceCentroid(f);
    }
    const std::vector<char> targetVisible = seenBy(model, o.intrinsics, middle, centroids);
    for (int f = 0; f < mesh.numberOfFaces(); ++f)
    {
      if (targetVisible[f] && mesh.faceNormals()[f].dot(middle.centre - centroids[f]) > 0.0)
      {
        trial.targetsCT.push_back(centroids[f]);
      }
    }
    if (trial.targetsCT.size() < 20)
    {
      continue; // the middle camera sees too little
    }

    // Points: uniform over the visible area, by rejection in batches.
    std::vector<Eigen::Vector3d> truePoints;
    std::vector<int> observer;
    for (int batch = 0; batch < 200 && static_cast<int>(truePoints.size()) < o.points; ++batch)
    {
      std::vector<Eigen::Vector3d> candidates(2000);
      for (Eigen::Vector3d& c : candidates)
      {
        const double a = rng.uniform(0.0, area);
        const int face =
          static_cast<int>(std::lower_bound(cumulativeArea.begin(), cumulativeArea.end(), a) -
            cumulativeArea.begin());
        c = randomPointOnFace(dataMesh, std::min(face, dataMesh.numberOfFaces() - 1), rng);
      }
      std::vector<std::vector<char>> seen;
      for (const CameraPose& camera : trial.trueCamerasCT)
      {
        seen.push_back(seenBy(dataSurface, o.intrinsics, camera, candidates));
      }
      for (size_t i = 0; i < candidates.size() && static_cast<int>(truePoints.size()) < o.points;
           ++i)
      {
        std::vector<int> cameras;
        for (int c = 0; c < o.cameras; ++c)
        {
          if (seen[c][i])
          {
            cameras.push_back(c);
          }
        }
        if (!cameras.empty())
        {
          truePoints.push_back(candidates[i]);
          observer.push_back(cameras[rng.index(static_cast<int>(cameras.size()))]);
        }
      }
    }
    if (static_cast<int>(truePoints.size()) < o.points)
    {
      continue;
    }

    // Noisy SfM cameras (before misalignment).
    std::vector<CameraPose> noisyCameras;
    for (const CameraPose& truth : trial.trueCamerasCT)
    {
      CameraPose noisy;
      noisy.rotation =
        rotationFromVector(rng.uniform(0.0, o.poseNoiseMaxDeg) * Degree * rng.direction()) *
        truth.rotation;
      noisy.centre = truth.centre + rng.uniform(0.0, o.poseNoiseMaxMm) * rng.direction();
      noisyCameras.push_back(noisy);
    }

    // Misalignment M about the data centroid; the data lives in M's frame.
    // V-IMLOP starts from identity, so M must leave every camera inside the
    // airway (its anatomical constraint needs a valid start): draw again
    // until it does.
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : truePoints)
    {
      centroid += p;
    }
    centroid /= static_cast<double>(truePoints.size());
    std::vector<VideoFrame> noisyFrames(noisyCameras.size());
    for (size_t c = 0; c < noisyCameras.size(); ++c)
    {
      noisyFrames[c].frameId = static_cast<int>(c);
      noisyFrames[c].cameraToSfm = noisyCameras[c];
    }
    SimilarityTransform misalign;
    SimilarityTransform start; // SfM to CT: identity, or scaled by the start's error
    bool inside = false;
    for (int draw = 0; draw < 200 && !inside; ++draw)
    {
      misalign.rotation = rotationFromVector(
        rng.uniform(o.misalignMinDeg, o.misalignMaxDeg) * Degree * rng.direction());
      misalign.translation = centroid - misalign.rotation * centroid +
        rng.uniform(o.misalignMinMm, o.misalignMaxMm) * rng.direction();
      if (o.startScaleError == 0.0)
      {
        inside = camerasInside(model, noisyFrames, misalign);
        continue;
      }
      // Scaled about the mean camera centre in the SfM frame, so that the
      // cameras move least; the start must still leave them inside.
      Eigen::Vector3d camerasSfm = Eigen::Vector3d::Zero();
      for (const VideoFrame& frame : noisyFrames)
      {
        camerasSfm += misalign.apply(frame.cameraToSfm.centre);
      }
      camerasSfm /= static_cast<double>(noisyFrames.size());
      start.scale = 1.0 + o.startScaleError;
      start.translation = (1.0 - start.scale) * camerasSfm;
      inside = camerasInside(model, noisyFrames, start.compose(misalign));
    }
    if (!inside)
    {
      continue;
    }
    trial.truthSfmToCT = misalign.inverse();
    trial.initialSfmToCT = start;

    for (size_t i = 0; i < truePoints.size(); ++i)
    {
      const Eigen::Vector3d axis = trial.trueCamerasCT[observer[i]].viewDirection();
      const Eigen::Matrix3d covarianceCT =
        viewAlignedCovariance(axis, o.sigmaAlongMm, o.sigmaAcrossMm);
      const Eigen::Matrix3d L = covarianceCT.llt().matrixL();
      const Eigen::Vector3d noisy =
        truePoints[i] + L * Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal());
      trial.data.points.push_back(misalign.apply(noisy));
      trial.data.pointCovariances.push_back(
        misalign.rotation * covarianceCT * misalign.rotation.transpose());
    }

    bool enoughContours = true;
    for (int c = 0; c < o.cameras; ++c)
    {
      const CameraPose& truth = trial.trueCamerasCT[c];
      VideoFrame frame;
      frame.frameId = c;
      frame.intrinsics = o.intrinsics;
      CameraPose noisy;
      noisy.rotation =
        rotationFromVector(rng.uniform(0.0, o.poseNoiseMaxDeg) * Degree * rng.direction()) *
        truth.rotation;
      noisy.centre = truth.centre + rng.uniform(0.0, o.poseNoiseMaxMm) * rng.direction();
      frame.cameraToSfm = misalign.apply(noisy);

      OccludingContourOptions contourOptions;
      contourOptions.sampleSpacingPx = o.contourSpacingPx;
      for (const ModelContourPoint& sample :
        visibleModelContours(dataSurface, o.intrinsics, truth, contourOptions))
      {
        ContourPoint p;
        p.pixel = sample.pixel + o.contourNoisePx * Eigen::Vector2d(rng.normal(), rng.normal());
        p.normal = sample.pixelNormal;
        if (o.contourNormalKappa > 0.0)
        {
          // Drawn only with the noise on, so that data without it stay as they were.
          p.normal = Eigen::Rotation2Dd(rng.normal() / std::sqrt(o.contourNormalKappa)) * p.normal;
        }
        frame.contour.push_back(p);
      }
      enoughContours = enoughContours && frame.contour.size() >= 10;
      trial.data.frames.push_back(frame);
    }
    // The frames' cameras had noise of their own: they too must start inside
    // (drawn again otherwise, rather than a registration that refuses them;
    // rare next to the model itself, less so next to a finer data surface).
    if (!enoughContours || !camerasInside(model, trial.data.frames, trial.initialSfmToCT))
    {
      continue;
    }
    return trial;
  }
  throw Error(
    "synthetic experiment: found no camera path whose views show enough surface and contours");
}

SyntheticOptions SyntheticOptions::paper()
{
  SyntheticOptions o;
  o.contourNoisePx = 3.0;
  o.contourNormalKappa = 200.0;
  return o;
}

} // namespace vimlop
