#ifndef vimlop_ReportFixture_h
#define vimlop_ReportFixture_h

// A small, fully determined registration record for the result-folder and
// report tests: P1-like data on the in-memory cavity, and a made-up result
// (the truth off by a small known motion, reached in 8 iterations), so that
// the pictures depend on neither the registration's numerics nor its speed.

#include "TestMeshes.h"
#include <vimlop/Core/Rotation.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Rendering/PNGImageIO.h>
#include <vimlop/Rendering/SurfaceView.h>
#include <vimlop/Results/RegistrationRecord.h>

#include <vtkImageData.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

namespace vimlop::fixtures
{

/// The record; with `imageFolder`, the frames' pictures (the model seen from
/// the true cameras) are written into `imageFolder`/frames (needs a display).
inline RegistrationRecord makeReportRecord(const std::string& imageFolder = std::string())
{
  const TriangleMesh mesh = makeCavityWithBlobs();
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  SyntheticOptions synthetic;
  synthetic.points = 200;
  synthetic.cameras = 3;
  const SyntheticTrial trial = makeSyntheticTrial(model, synthetic, 5);

  RegistrationRecord record;
  record.source = "report fixture";
  record.model = mesh;
  record.data = trial.data;
  record.initialSfmToCT = trial.initialSfmToCT;
  record.truth =
    RegistrationRecord::GroundTruth{ trial.truthSfmToCT, trial.trueCamerasCT, trial.targetsCT };

  SimilarityTransform offset;
  offset.rotation = rotationFromVector(Eigen::Vector3d(0.3, 0.0, 0.0) * M_PI / 180.0);
  offset.translation = Eigen::Vector3d(0.1, 0.0, 0.0);
  const SimilarityTransform final = offset.compose(trial.truthSfmToCT);
  const Vector7d path = final.compose(trial.initialSfmToCT.inverse()).log();
  RegistrationResult& result = record.result;
  for (int i = 1; i <= 8; ++i)
  {
    IterationRecord r;
    r.iteration = i;
    r.withContours = i > 3;
    const double done = 1.0 - std::pow(0.5, i - 1);
    r.transform = SimilarityTransform::exp(done * path).compose(trial.initialSfmToCT);
    r.updated =
      SimilarityTransform::exp((1.0 - std::pow(0.5, i)) * path).compose(trial.initialSfmToCT);
    r.cost3d = 800.0 * std::pow(0.5, i) + 20.0;
    r.cost2d = r.withContours ? 300.0 * std::pow(0.6, i) + 15.0 : 0.0;
    r.cost = r.cost3d + r.cost2d;
    r.pointInliers = 190;
    r.contourMatches = r.withContours ? 400 : 0;
    r.contourInliers = r.withContours ? 380 : 0;
    r.residualErrorMm = 0.3 + 2.0 * std::pow(0.5, i);
    r.contourErrorPx = r.withContours ? 1.0 + 6.0 * std::pow(0.5, i - 3) : 0.0;
    result.history.push_back(r);
  }
  result.sfmToCT = final;
  result.termination = TerminationReason::Converged;
  result.iterations = 8;
  result.runtimeSeconds = 0.5;
  result.residualErrorMm = 0.31;
  result.contourErrorPx = 1.2;
  result.contourErrorInliersPx = 1.1;
  for (const Eigen::Vector3d& x : trial.data.points)
  {
    result.pointInliers.push_back(1);
    result.pointMatches.push_back(final.apply(x));
  }
  result.pointInliers[0] = 0;
  for (const VideoFrame& frame : trial.data.frames)
  {
    FrameResult f;
    f.frameId = frame.frameId;
    f.cameraToCT = final.apply(frame.cameraToSfm);
    f.contourPoints = static_cast<int>(frame.contour.size());
    f.matched = f.contourPoints;
    f.inliers = f.contourPoints - 2;
    f.contourErrorPx = 1.2;
    f.contourErrorInliersPx = 1.1;
    f.visibleModelSamples = 3 * f.contourPoints;
    for (int i = 0; i < 3 && i < f.contourPoints; ++i)
    {
      ContourCorrespondence c;
      c.video = i;
      c.videoPixel = frame.contour[static_cast<size_t>(i)].pixel;
      c.modelPixel = c.videoPixel + Eigen::Vector2d(0.5, -0.25);
      c.modelPoint = Eigen::Vector3d(1.0, 2.0, 3.0 + i);
      c.inlier = i != 1;
      f.correspondences.push_back(c);
    }
    result.frames.push_back(f);
  }

  if (!imageFolder.empty())
  {
    std::filesystem::create_directories(std::filesystem::path(imageFolder) / "frames");
    for (size_t j = 0; j < trial.data.frames.size(); ++j)
    {
      char name[64];
      std::snprintf(name, sizeof name, "frames/frame-%04d.png", trial.data.frames[j].frameId);
      writePNG(renderSurfaceView(mesh, trial.data.frames[j].intrinsics, trial.trueCamerasCT[j]),
        (std::filesystem::path(imageFolder) / name).string());
      record.frameImages.push_back(name);
    }
  }
  return record;
}

} // namespace vimlop::fixtures

#endif
