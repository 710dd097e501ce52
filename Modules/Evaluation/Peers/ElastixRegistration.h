#ifndef vimlop_ElastixRegistration_h
#define vimlop_ElastixRegistration_h

#include <vimlop/Imaging/CTVolume.h>

#include <array>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief How to run elastix.
struct ElastixRegistrationOptions
{
  /// elastix parameter files, applied in order (e.g. affine then B-spline). Required.
  std::vector<std::string> parameterFiles;
  /// Folder for the images, points, logs and results; created if missing. Required.
  std::string workDirectory;
  /// The programs: names looked up on PATH, or paths. Defaults "elastix", "transformix".
  std::string elastix = "elastix";
  std::string transformix = "transformix";
  /// Threads for elastix; 0 lets it choose. Default 0.
  int threads = 0;
};

/**
 * @brief Registration by the elastix program (a peer for comparisons,
 * DESIGN section 8): runs `elastix` on a fixed and a moving CT with the
 * given parameter files, then `transformix` to carry points of the fixed CT
 * into the moving CT.
 *
 * elastix, like ITK, estimates the transform from fixed-image points to
 * moving-image points, and transformix applies it to points of the fixed
 * image: with the template fixed, template points come out in the patient.
 * Both programs run as separate processes in `workDirectory`, which holds
 * their inputs, logs and results afterwards.
 */
struct ElastixRegistration
{
  /// The fixed points carried into the moving CT's frame (mm), in order.
  std::vector<std::array<double, 3>> movingPoints;
  /// Wall-clock time of the elastix run (s), and of the transformix run.
  double registrationSeconds = 0.0;
  double transformSeconds = 0.0;

  /// @brief True when both programs can be run (`--version` succeeds).
  static bool available(const ElastixRegistrationOptions& options);

  /**
   * @brief Registers `fixed` to `moving` and carries `fixedPoints` (fixed CT frame, mm) over.
   * @throws vimlop::Error when a program is missing or fails (naming its log
   * file), a parameter file is missing, or the output cannot be read.
   */
  static ElastixRegistration compute(const CTVolume& fixed, const CTVolume& moving,
    const std::vector<std::array<double, 3>>& fixedPoints,
    const ElastixRegistrationOptions& options);
};

} // namespace vimlop

#endif
