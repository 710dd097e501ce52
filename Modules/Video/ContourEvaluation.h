#ifndef vimlop_ContourEvaluation_h
#define vimlop_ContourEvaluation_h

#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Core/DepthMap.h>
#include <vimlop/Core/ModelContourPoint.h>

#include <vector>

namespace vimlop
{

/// @brief Matching tolerance and the visibility rule of the truth.
struct ContourEvaluationOptions
{
  /// Distance within which a detection matches the truth, pixels (default 2).
  double tolerancePx = 2.0;
  /// Least relative depth step for a true sample to count for recall (default 0.15).
  double minDepthGap = 0.15;
  /// Distance along the normal at which the far side's depth is read, pixels (default 3).
  double depthProbePx = 3.0;
  /// True samples this close to the border are left out of recall, pixels (default 5).
  double borderPx = 5.0;
};

/**
 * @brief Scores of detected contour points against the true occluding
 * contours of a simulated frame, pooled over any number of frames.
 *
 * The truth is the model's own definition (V3): the mesh's occluding
 * contours at the true camera pose (extractOccludingContours, 1 px samples)
 * that are visible (V4). They are exactly where the rendered picture has its
 * depth discontinuities, since the picture is a render of that mesh, and they
 * are what the registration matches video contours to; they also give the
 * true normal. But a contour whose far side is hardly farther than its near
 * side (a fold seen edge-on in front of the wall it belongs to) makes no
 * visible step in any picture: with the light at the camera, a depth step of
 * 15 % changes the light by about 30 %, and the gamma-encoded picture by about
 * 13 %, no more than the mucosa's own colour variation. So recall counts only
 * the true samples whose far side, probed in the rendered depth map
 * `depthProbePx` along the normal, is at least `minDepthGap` (relative)
 * deeper than the sample. Precision counts a detected point as correct when it
 * lies within `tolerancePx` of any visible true sample, with or without a step.
 */
class ContourEvaluation
{
public:
  ContourEvaluation();
  explicit ContourEvaluation(const ContourEvaluationOptions& options);

  /**
   * @brief Adds one frame: its detected points, the visible true samples
   * (pixel, pixelNormal and the 3-D point in the camera's world) and the
   * frame's true depth map and camera z of each sample (`sampleDepthMm`).
   */
  void addFrame(const std::vector<ContourPoint>& detected,
    const std::vector<ModelContourPoint>& visibleTruth, const std::vector<double>& sampleDepthMm,
    const DepthMap& depth);

  /// @brief Fraction of detected points within the tolerance of the truth (0 without detections).
  double precision() const;
  /// @brief Fraction of true samples with a step within the tolerance of a detection.
  double recall() const;
  /// @brief Median angle between a matched detection's normal and the truth's, degrees.
  double medianNormalErrorDeg() const;
  /// @brief Every matched detection's normal error, degrees.
  const std::vector<double>& normalErrorsDeg() const { return this->NormalErrorsDeg; }

  int detectedPoints() const { return this->Detected; }
  int correctDetections() const { return this->Correct; }
  int truthPoints() const { return this->Truth; }
  int truthFound() const { return this->Found; }

private:
  ContourEvaluationOptions Opts;
  int Detected = 0;
  int Correct = 0;
  int Truth = 0;
  int Found = 0;
  std::vector<double> NormalErrorsDeg;
};

} // namespace vimlop

#endif
