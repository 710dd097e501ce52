#ifndef vimlop_ContourScoring_h
#define vimlop_ContourScoring_h

#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Video/OccludingContourDetector.h>

#include <vector>

namespace vimlop
{

/// @brief How well the detected contours of a simulated sequence match the
/// true ones (NaN when not scored: distorted frames).
struct ContourScores
{
  double precision = 0.0;
  double recall = 0.0;
  /// Median angle between detected and true contour normals, degrees.
  double normalErrorDegMedian = 0.0;
};

/// @brief The contours detected on a simulated sequence, and their scores.
struct ScoredContours
{
  /// Per frame, the detected contour thinned to the detector's spacing (what registration uses).
  std::vector<std::vector<ContourPoint>> contoursPerFrame;
  ContourScores scores;
};

/**
 * @brief Detects the occluding contours of every frame of `video` (densely,
 * with `detector` but no spacing) and scores them against the true
 * occluding contours of `model` seen from the true cameras (those visible,
 * with their depths, ContourEvaluation); returns them thinned to
 * `detector.spacingPx`.
 */
ScoredContours detectAndScoreContours(const RegistrationModel& model, const SimulatedVideo& video,
  const ContourDetectionOptions& detector);

} // namespace vimlop

#endif
