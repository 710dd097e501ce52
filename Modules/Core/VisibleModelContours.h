#ifndef vimlop_VisibleModelContours_h
#define vimlop_VisibleModelContours_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/ModelContourPoint.h>
#include <vimlop/Core/OccludingContours.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/RegistrationModel.h>

#include <vector>

namespace vimlop
{

struct StageTimes;

/**
 * @brief The model's occluding contours that a camera sees (V3 and V4): the
 * samples extractOccludingContours() finds on `model.mesh()`, kept when
 * `model.visibility()` classifies them visible, in extraction order.
 *
 * This is the one definition of "the model contours a camera sees": the
 * registration matches video contours to them, the synthetic experiment makes
 * its video contours from them, and trajectory planning counts them, so that
 * all of them agree on one picture of the model.
 *
 * @param cameraToCT the camera's pose in the CT frame (mm)
 * @param times when given, the wall-clock time of extraction (V3) and of the
 *   visibility test (V4) is added to `contoursMs` and `visibilityMs`
 */
std::vector<ModelContourPoint> visibleModelContours(const RegistrationModel& model,
  const PinholeCamera& intrinsics, const CameraPose& cameraToCT,
  const OccludingContourOptions& options = OccludingContourOptions(), StageTimes* times = nullptr);

} // namespace vimlop

#endif
