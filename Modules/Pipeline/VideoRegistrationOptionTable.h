#ifndef vimlop_VideoRegistrationOptionTable_h
#define vimlop_VideoRegistrationOptionTable_h

/**
 * @file VideoRegistrationOptionTable.h
 * @brief The main job's own scalar settings (VideoRegistrationOptions beyond
 * its RegistrationOptions, which have RegistrationOptionTable.h) as one
 * table, with the same columns: X(Name, Type, member, key, flag, min, max,
 * help), `member` a field of VideoRegistrationOptions. From it come the VTK
 * properties of vtkVIMLOPVideoRegistration, the flags of `vimlop register`
 * and `vimlop evaluate video`, the JSON of `--print-options` and
 * VideoRegistrationOptions::validate(). Not in the table: the lists (scale
 * factors, canonical rolls), the contour detector's channel and the field
 * stop's mode (`--field-stop`).
 */

// clang-format off
#define VIMLOP_VIDEO_REGISTRATION_VALUES(X) \
  X(ScaleBoundFactor, double, scaleBoundFactor, "scale_bound_factor", "--scale-bound", 1.0001, \
    10.0, "V7: scale bounds: the initial scale divided and multiplied by this") \
  X(PointNoiseFloorMm, double, pointNoiseFloorMm, "point_noise_floor_mm", "--point-noise-mm", \
    0.0, 100.0, "V1: std added to every SfM point's covariance, mm") \
  X(ScreeningIterations, int, multiStart.screeningIterations, "screening_iterations", \
    "--screen-iterations", 0, 100000, \
    "V13: iterations of every start before the finalists are chosen (0: all run fully)") \
  X(ScreeningStride, int, multiStart.screeningStride, "screening_stride", "--screening-stride", \
    1, 1000, "V13: screening registers every n-th frame and SfM point") \
  X(Finalists, int, multiStart.finalists, "finalists", "--finalists", 1, 100000, \
    "V13: starts run fully after screening, at every scale factor") \
  X(FailureThresholdPx, double, multiStart.failureContourErrorPx, "failure_threshold_px", \
    "--failure-threshold-px", 0.01, 10000.0, \
    "V13: contour error above which the result is flagged as a failure, px") \
  X(FailureResidualMm, double, multiStart.failureResidualErrorMm, "failure_residual_mm", \
    "--failure-residual-mm", 0.001, 1000.0, \
    "V13: 3-D residual above which the result is flagged as a failure, mm") \
  X(MinMatchedFraction, double, multiStart.minMatchedFraction, "min_matched_fraction", \
    "--min-matched-fraction", 0.0, 1.0, \
    "V13: least fraction of video contour points matched, else flagged as a failure") \
  X(CanonicalSpacingMm, double, canonical.spacingMm, "canonical_spacing_mm", \
    "--canonical-spacing-mm", 0.1, 100.0, "V13: distance between canonical positions, mm") \
  X(CanonicalClearanceMm, double, canonical.minClearanceMm, "canonical_clearance_mm", \
    "--canonical-clearance-mm", 0.0, 50.0, "V13: least distance of a canonical position to the wall, mm") \
  X(CanonicalLookAheadMm, double, canonical.lookAheadMm, "canonical_look_ahead_mm", \
    "--canonical-look-ahead-mm", 0.1, 200.0, "V13: free length needed ahead of a canonical camera, mm") \
  X(CanonicalViewsPerPosition, int, canonical.viewsPerPosition, "canonical_views_per_position", \
    "--canonical-views", 1, 26, "V13: view directions per canonical position") \
  X(ContourSmoothingSigmaPx, double, contours.smoothingSigmaPx, "contour_smoothing_sigma_px", \
    "--contour-sigma-px", 0.3, 20.0, "V1: Gaussian smoothing before the contour gradient, px") \
  X(ContourHighThreshold, double, contours.highThreshold, "contour_high_threshold", \
    "--contour-high-threshold", 1e-4, 10.0, "V1: upper hysteresis threshold on the log-intensity gradient") \
  X(ContourLowThreshold, double, contours.lowThreshold, "contour_low_threshold", \
    "--contour-low-threshold", 1e-4, 10.0, "V1: lower hysteresis threshold on the log-intensity gradient") \
  X(ContourSpacingPx, double, contours.spacingPx, "contour_spacing_px", "--contour-spacing-px", \
    0.0, 100.0, "V1: least distance between detected contour points, px") \
  X(FieldStopMarginPx, double, fieldOfView.marginPx, "field_stop_margin_px", \
    "--field-stop-margin-px", 0.0, 200.0, \
    "pixels within this distance of the field stop's edge are not used, px") \
  X(FieldStopThreshold, double, fieldOfView.autoThresholdGrey, "field_stop_threshold", \
    "--field-stop-threshold", 0.0, 254.0, \
    "automatic field stop: brightest grey level over the frames at or below which a pixel is border")
// clang-format on

#endif
