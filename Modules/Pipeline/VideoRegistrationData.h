#ifndef vimlop_VideoRegistrationData_h
#define vimlop_VideoRegistrationData_h

#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Video/SfmReconstruction.h>

#include <vector>

namespace vimlop
{

/**
 * @brief The registration data (V1) of a video: every frame SfM registered,
 * with its SfM-frame camera, its intrinsics without distortion (the frames
 * were undistorted before SfM and contour detection) and its contours; every
 * SfM point with its covariance in mm², i.e. the SfM covariance scaled by
 * `initialScale`² (SfM units to mm, V14; the registration keeps it fixed)
 * plus `pointNoiseFloorMm`² I (what triangulation geometry does not capture:
 * the model's own error, calibration).
 *
 * @param contoursPerFrame one list per SfM frame, in the order of `sfm.frames`.
 * @param frameOf when given, receives for each data frame its index in `sfm.frames`.
 * @param frameIds when given (one per SfM frame), the frames' ids
 * (FrameSequence::ids()); otherwise a frame's id is its index.
 * @throws vimlop::Error when the contour lists do not match the SfM frames,
 * or the scale or noise floor is not a positive (non-negative) number.
 */
RegistrationData makeVideoRegistrationData(const SfmReconstruction& sfm,
  const std::vector<std::vector<ContourPoint>>& contoursPerFrame, double initialScale,
  double pointNoiseFloorMm, std::vector<int>* frameOf = nullptr,
  const std::vector<int>* frameIds = nullptr);

} // namespace vimlop

#endif
