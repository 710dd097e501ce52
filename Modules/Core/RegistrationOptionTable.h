#ifndef vimlop_RegistrationOptionTable_h
#define vimlop_RegistrationOptionTable_h

/**
 * @file RegistrationOptionTable.h
 * @brief The scalar settings of RegistrationOptions as one table, from which
 * every face is generated: the VTK setters (clamped into the range) and
 * PrintSelf of vtkVIMLOPRegistration and vtkVIMLOPVideoRegistration, the JSON
 * of result.json and `--print-options`, the command-line flags of `vimlop
 * register` and `vimlop evaluate video`, and RegistrationOptions::validate().
 *
 * Adding a setting: declare it in RegistrationOptions (documented: paper
 * element, unit, default, why) and add its row here; nothing else.
 *
 * VIMLOP_REGISTRATION_VALUES(X) calls
 *   X(Name, Type, member, key, flag, min, max, help)
 * for each numeric setting: `Name` the VTK property (SetName/GetName),
 * `member` the field of RegistrationOptions, `key` the JSON key, `flag` the
 * command-line flag, [min, max] the closed range of valid values, `help` one
 * line with the paper element and the unit.
 *
 * VIMLOP_REGISTRATION_SWITCHES(X) calls X(Name, member, key, flag, help) for
 * each on/off setting (VTK NameOn/NameOff; flags --flag and --no-flag).
 *
 * Not in the table, because they are not one scalar: the method (an enum),
 * Σ2d (a matrix), and the scale bounds (a pair whose order is checked; the
 * main job sets them from its scale bound factor).
 */

// clang-format off
#define VIMLOP_REGISTRATION_VALUES(X) \
  X(ContourKappa, double, contourMatch.kappa, "contour_kappa", "--kappa", 0.0, 1e6, \
    "V5: von Mises concentration kappa of contour normals (paper: 200)") \
  X(MaxContourNormalAngleDeg, double, contourMatch.maxAngleDeg, "max_contour_normal_angle_deg", \
    "--max-normal-angle-deg", 1.0, 180.0, "V5: largest angle between matched contour normals, deg") \
  X(ContourSampleSpacingPx, double, contourSampleSpacingPx, "contour_sample_spacing_px", \
    "--contour-sample-spacing-px", 0.05, 50.0, "V3: spacing of model contour samples, px") \
  X(TrimFraction, double, trimFraction, "trim_fraction", "--trim", 0.0, 0.9, \
    "V8: initial trim ratio p_t of 3-D pairs") \
  X(ChiSquareProbability, double, chiSquareProbability, "chi_square_probability", "--chi2-p", \
    0.5, 0.99999, "V8: chi-square outlier test probability") \
  X(MaxContourOutlierFraction, double, maxContourOutlierFraction, \
    "max_contour_outlier_fraction", "--max-contour-outliers", 0.0, 1.0, \
    "V8: largest fraction of a frame's contour points rejected as outliers") \
  X(MaxBackoffSteps, int, maxBackoffSteps, "max_backoff_steps", "--max-backoff-steps", 0, 60, \
    "V10: halvings of an update that leaves the airway before it is undone") \
  X(MaxIterations, int, maxIterations, "max_iterations", "--max-iterations", 1, 100000, \
    "V11: iteration cap per start") \
  X(ConvergenceTranslationMm, double, convergenceTranslationMm, "convergence_translation_mm", \
    "--convergence-mm", 0.0, 10.0, "V11: converged below this motion of the data centroid, mm") \
  X(ConvergenceRotationDeg, double, convergenceRotationDeg, "convergence_rotation_deg", \
    "--convergence-deg", 0.0, 10.0, "V11: ... and below this rotation change, deg") \
  X(ConvergenceScaleRelative, double, convergenceScaleRelative, "convergence_scale_relative", \
    "--convergence-scale", 0.0, 0.1, "V11: ... and below this relative scale change") \
  X(MaxAcceleration, double, maxAcceleration, "max_acceleration", "--max-acceleration", 1.0, \
    1000.0, "largest extrapolation along consistent updates, times the last update") \
  X(StallRelativeDecrease, double, stallRelativeDecrease, "stall_relative_decrease", \
    "--stall-decrease", 0.0, 1.0, "V11: stall when the mean cost falls by less than this fraction") \
  X(StallIterations, int, stallIterations, "stall_iterations", "--stall-iterations", 1, 100000, \
    "V11: ... over this many iterations") \
  X(PoseUpdateMaxIterations, int, poseUpdate.maxIterations, "pose_update_max_iterations", \
    "--pose-update-iterations", 1, 1000, "V6: Levenberg-Marquardt iterations per pose update") \
  X(PoseUpdateRelativeTolerance, double, poseUpdate.relativeTolerance, \
    "pose_update_relative_tolerance", "--pose-update-tolerance", 0.0, 1.0, \
    "V6: the update stops when its cost falls by less than this fraction") \
  X(NumberOfThreads, int, threads, "threads", "--threads", 0, 1024, \
    "threads, 0 for all cores (results do not depend on it)")

#define VIMLOP_REGISTRATION_SWITCHES(X) \
  X(EqualInfluence, equalInfluence, "equal_influence", "--equal-influence", \
    "V9: scale the 3-D covariances so that 3-D and 2-D data weigh the same") \
  X(AnatomicalConstraint, anatomicalConstraint, "anatomical_constraint", \
    "--anatomical-constraint", "V10: keep every camera inside the airway (never for trimmed ICP)") \
  X(Accelerate, accelerate, "accelerate", "--accelerate", \
    "Besl-McKay extrapolation along consistent updates") \
  X(PointsFirst, pointsFirst, "points_first", "--points-first", \
    "V-IMLOP: leave the contours out until the points alone converge") \
  X(RobustContourInflation, robustContourInflation, "robust_contour_inflation", \
    "--robust-contour-inflation", \
    "V8: inflate the contour tests by the median match error, not the mean")
// clang-format on

#endif
