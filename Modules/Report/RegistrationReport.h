#ifndef vimlop_RegistrationReport_h
#define vimlop_RegistrationReport_h

#include <vimlop/Results/PerturbationRuns.h>
#include <vimlop/Results/RegistrationRecord.h>
#include <vimlop/Results/RegistrationVerdict.h>

#include "VIMLOPReportModule.h"

#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

class RegistrationModel;

/// @brief Picture sizes, pixels.
struct RegistrationReportOptions
{
  int sceneWidthPx = 800;  ///< default 800
  int sceneHeightPx = 600; ///< default 600
  int chartWidthPx = 520;  ///< per chart (default 520)
  int chartHeightPx = 380; ///< default 380
  /// At most this many frames get an overlay, evenly spread (default 0: every frame).
  int maxOverlayFrames = 0;
  /// The scope in the CT's slices (`ct-slices.png`; default on), from `ctPath`.
  bool ctSlices = true;
  /**
   * The CT to draw the slices from. Empty (the default): the CT the record
   * names as its "ct" input, when it is still there; a recorded CT that
   * cannot be read any more is said so in the page instead of the slices,
   * while a CT given here that cannot be read is an error.
   */
  std::string ctPath;
};

/**
 * @brief The rendered report of a registration (and of a perturbation study),
 * as `vimlop report` writes it, and the numbers it holds.
 *
 * write() renders offscreen with VTK (needs an X display) into the output folder:
 * - `overlays/frame-<id>.png`: per frame, the frame's picture with the
 *   model's visible occluding contours in green (drawn by
 *   vtkVIMLOPSilhouetteRenderer) and the video contour points in white,
 *   before registration (cameras at the initial transform) on the left and
 *   after on the right, as in the paper's Fig. 2;
 * - `scene.png`: the model cut open, the registered points in red, the
 *   camera path as arrows (and the true cameras in cyan) (Fig. 1b), and the
 *   same scene to turn and zoom in the page (`scene-data.js`, `view3d.js`:
 *   WebGL, offline);
 * - at the top of `index.html`, the verdict (RegistrationVerdict):
 *   registered, flagged as a failure (do not navigate) or not checked, with
 *   the contour error against the threshold, as an element with id
 *   "verdict" and class "registered", "flagged" or "unchecked";
 * - `frames.png`: per frame, the contour error before and after beside the
 *   failure threshold, and with ground truth the camera errors;
 * - `ct-slices.png` (with a CT, RegistrationReportOptions::ctPath): the
 *   axial, coronal and sagittal slices through the optical centre of the
 *   middle frame, the scope and its view direction drawn in them;
 * - `iterations.png`: the cost per iteration (log scale) beside the errors
 *   per iteration (residual mm, contour px, and with ground truth TRE and
 *   mean camera position error, mm);
 * - `perturbation.png` (with runs): final error and contour error against
 *   the initial offset, successes in blue and failures in red (Fig. 3);
 * - `report.json` (format "vimlop-report", version 1) with the numbers (and
 *   "verdict": status, headline, contour error, threshold, reason; "run":
 *   command line, run time, versions, inputs) and `index.html` tying
 *   pictures, metrics, the run and the parameters together.
 * The contour errors before and after are measured the same way for both:
 * the mean distance from each video contour point to its V5 match among the
 * model's visible contour samples (Embree visibility), pixels.
 */
class VIMLOPREPORT_EXPORT RegistrationReport
{
public:
  /// @brief The numbers of one frame.
  struct Frame
  {
    int frameId = 0;
    double contourErrorBeforePx = 0.0;
    double contourErrorAfterPx = 0.0;
    int matchedBefore = 0;
    int matchedAfter = 0;
    /// With ground truth: distance and angle of the registered camera from the true one.
    std::optional<double> cameraPositionErrorMm;
    std::optional<double> cameraAngleErrorDeg;
    /// The overlay picture, relative to the report folder (empty when not drawn).
    std::string overlay;
  };

  /**
   * @brief Writes the report of `record` (null when only a perturbation study
   * is reported) whose frame pictures are relative to `resultFolder`, and of
   * `runs` (may be empty), into `outFolder` (created if needed).
   * `model` is the record's model made ready for queries with Embree
   * visibility (makeEmbreeRegistrationModel(), e.g. the one the registration
   * used), or null to build it here.
   * @throws vimlop::Error for nothing to report, a frame picture that cannot
   * be read or does not fit its intrinsics, or a file that cannot be written.
   */
  static RegistrationReport write(const RegistrationRecord* record, const std::string& resultFolder,
    const std::vector<PerturbationRun>& runs, const std::string& outFolder,
    const RegistrationReportOptions& options, const RegistrationModel* model = nullptr);

  std::vector<Frame> frames;
  /// Mean over frames of the contour errors, pixels (0 without frames).
  double contourErrorBeforePx = 0.0;
  double contourErrorAfterPx = 0.0;
  /// With ground truth and targets: the TRE of the start and of the result, mm.
  std::optional<double> treBeforeMm;
  std::optional<double> treAfterMm;
  /// The verdict on the record's result (none for a perturbation study alone).
  std::optional<RegistrationVerdict> verdict;
  /// Every picture written, relative to the report folder.
  std::vector<std::string> pictures;
  /// The text of report.json, as written (e.g. for `vimlop report --json`).
  std::string reportJson;
};

} // namespace vimlop

#endif
