#ifndef vimlop_TrialSaving_h
#define vimlop_TrialSaving_h

#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/RegistrationResult.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Core/TriangleMesh.h>

#include <string>

namespace vimlop
{

/**
 * @brief Writes a synthetic trial and its registration as a result folder
 * (see RegistrationRecordIO.h), with the ground truth and, as the frames'
 * pictures (P1 has no video), the model rendered from each true camera
 * (renderSurfaceView). Needs an X display.
 * @throws vimlop::Error if a file cannot be written.
 */
void saveSyntheticTrial(const std::string& folder, const std::string& source,
  const TriangleMesh& mesh, const SyntheticTrial& trial, const RegistrationOptions& options,
  const RegistrationResult& result);

} // namespace vimlop

#endif
