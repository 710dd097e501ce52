#ifndef vimlop_RegistrationSummary_h
#define vimlop_RegistrationSummary_h

#include <vimlop/Core/Correspondences.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/RegistrationResult.h>
#include <vimlop/Core/SimilarityTransform.h>

/**
 * @file RegistrationSummary.h
 * @brief The metrics of an iteration and of a result (V12), from the matches at an estimate.
 */

namespace vimlop
{

/**
 * @brief Fills the match metrics of `record` from the matches at its
 * estimate: the inlier costs (C3d, C2d and their sum), inlier and match
 * counts, the mean 3-D match distance over inliers (mm) and the mean contour
 * match distance over every matched contour point (pixels), and the stage times.
 */
void summariseIteration(const Correspondences& matches, IterationRecord& record);

/**
 * @brief The result at T (without history, termination or runtime): T, the
 * 3-D inliers and matches, the residual error (mean distance of the
 * registered 3-D inliers to the surface by `model.locator()`, mm), and per
 * frame the camera in CT, its contour correspondences and contour errors
 * (pixels; all matches and inliers), with the same errors over all frames.
 *
 * @param matches found at `sfmToCT` with contours, so that every method's
 *   contour error can be compared
 */
RegistrationResult summariseRegistration(const RegistrationModel& model,
  const RegistrationData& data, const SimilarityTransform& sfmToCT, const Correspondences& matches);

} // namespace vimlop

#endif
