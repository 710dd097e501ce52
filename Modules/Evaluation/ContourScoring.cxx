#include <vimlop/Evaluation/ContourScoring.h>

#include <vimlop/Core/VisibleModelContours.h>
#include <vimlop/Video/ContourEvaluation.h>

namespace vimlop
{

ScoredContours detectAndScoreContours(const RegistrationModel& model, const SimulatedVideo& video,
  const ContourDetectionOptions& detectorOptions)
{
  // Scored densely: thinning would make precision and recall depend on spacing.
  ContourDetectionOptions denseOptions = detectorOptions;
  denseOptions.spacingPx = 0.0;
  const OccludingContourDetector detector(denseOptions);
  const PinholeCamera& k = video.intrinsics;
  ContourEvaluation evaluation;
  ScoredContours result;
  for (size_t f = 0; f < video.frames.size(); ++f)
  {
    const std::vector<ContourPoint> dense = detector.detect(video.frames[f]);
    std::vector<ModelContourPoint> truth;
    std::vector<double> depths;
    for (const ModelContourPoint& s : visibleModelContours(model, k, video.camerasCT[f]))
    {
      truth.push_back(s);
      depths.push_back(video.camerasCT[f].worldToCamera(s.point).z());
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
