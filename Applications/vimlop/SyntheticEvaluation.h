#ifndef vimlop_SyntheticEvaluation_h
#define vimlop_SyntheticEvaluation_h

#include "SyntheticExperiment.h"
#include "TriangleMesh.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief Settings of the P1 evaluation (the paper's synthetic experiment).
struct SyntheticEvaluationOptions
{
  int trials = 100;
  std::uint64_t seed = 1;
  SyntheticOptions synthetic;
  /// Any of "vimlop", "imlp", "trimmed-icp", "open3d-icp", "open3d-gicp".
  std::vector<std::string> methods = { "vimlop", "imlp", "trimmed-icp", "open3d-icp", "open3d-gicp" };
  /// A trial succeeds when its TRE is below this, mm (default 1).
  double successThresholdMm = 1.0;
  /// Scale bounds of VIMLOP's methods (the data's true scale is 1).
  double minScale = 0.8;
  double maxScale = 1.25;
  int threads = 0;
  /// When not empty: trial 0 and its registration by the first of V-IMLOP,
  /// IMLP, trimmed ICP among `methods` are written to this result folder
  /// (see TrialSaving.h; needs an X display).
  std::string saveTrialFolder;
};

/// @brief Every method name P1 knows, comma-separated (for messages).
const char* syntheticMethodNames();

/// @throws vimlop::Error naming the first unknown method, or if Open3D is asked for but unavailable.
void checkSyntheticMethods(const std::vector<std::string>& methods);

/**
 * @brief Runs P1: `trials` synthetic trials on `mesh`, every method on every
 * trial, and returns the JSON report (layout in the user guide). Writes a
 * progress line per trial to `progress` when given.
 * @throws vimlop::Error for an unknown method or an unusable mesh.
 */
nlohmann::json runSyntheticEvaluation(
  const TriangleMesh& mesh, const SyntheticEvaluationOptions& options, std::ostream* progress);

} // namespace vimlop

#endif
