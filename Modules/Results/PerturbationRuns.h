#ifndef vimlop_PerturbationRuns_h
#define vimlop_PerturbationRuns_h

#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief One registration of a robustness study (P3): how far its start was
 * perturbed and how it ended. The input of the report's Fig. 3 plot.
 *
 * In JSON (a file with a "runs" list of such objects, e.g. the P3
 * evaluation's output): {"offset_mm": ..., "offset_deg": ...,
 * "final_error_mm": ..., "contour_error_px": ..., "success": true|false}.
 */
struct PerturbationRun
{
  double offsetMm = 0.0;       ///< translation of the perturbed start, mm
  double offsetDeg = 0.0;      ///< rotation of the perturbed start, degrees
  double finalErrorMm = 0.0;   ///< error at the end, mm (e.g. mean camera position error)
  double contourErrorPx = 0.0; ///< mean contour error at the end, pixels
  bool success = false;        ///< whether the run met the study's success criterion
};

/**
 * @brief The "runs" of a perturbation-study JSON file.
 * @throws vimlop::Error naming the file for a missing or unreadable file, no
 * "runs" list, or a run without offset_mm, final_error_mm or contour_error_px.
 */
std::vector<PerturbationRun> readPerturbationRuns(const std::string& path);

/**
 * @brief Writes `runs` as {"runs": [...]} (for tests and for studies that keep
 * only the runs).
 * @throws vimlop::Error if the file cannot be written.
 */
void writePerturbationRuns(const std::vector<PerturbationRun>& runs, const std::string& path);

} // namespace vimlop

#endif
