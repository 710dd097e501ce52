#include "ContourScoring.h"

#include "ContourEvaluation.h"
#include "OccludingContours.h"

namespace vimlop
{

ScoredContours detectAndScoreContours(const RegistrationModel& model, const SimulatedVideo& video,
  const OccludingContourDetector::Options& detectorOptions)
{
  // Scored densely: thinning would make precision and recall depend on spacing.
  OccludingContourDetector::Options denseOptions = detectorOptions;
  denseOptions.spacingPx = 0.0;
  const OccludingContourDetector detector(denseOptions);
  const PinholeCamera& k = video.intrinsics;
  ContourEvaluation evaluation;
  ScoredContours result;
  for (size_t f = 0; f < video.frames.size(); ++f)
  {
    const std::vector<ContourPoint> dense = detector.detect(video.frames[f]);
    const std::vector<ModelContourPoint> samples =
      extractOccludingContours(model.mesh(), k, video.camerasCT[f]);
    std::vector<Eigen::Vector3d> points;
    for (const ModelContourPoint& s : samples)
    {
      points.push_back(s.point);
    }
    std::vector<char> visible;
    model.visibility().classify(k, video.camerasCT[f], points, visible);
    std::vector<ModelContourPoint> truth;
    std::vector<double> depths;
    for (size_t i = 0; i < samples.size(); ++i)
    {
      if (visible[i])
      {
        truth.push_back(samples[i]);
        depths.push_back(video.camerasCT[f].worldToCamera(samples[i].point).z());
      }
    }
    evaluation.addFrame(dense, truth, depths, video.depth[f]);
    result.contoursPerFrame.push_back(
      OccludingContourDetector::thin(dense, detectorOptions.spacingPx));
  }
  result.scores.precision = evaluation.precision();
  result.scores.recall = evaluation.recall();
  result.scores.normalErrorDegMedian = evaluation.medianNormalErrorDeg();
  return result;
}

} // namespace vimlop
