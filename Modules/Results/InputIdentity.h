#ifndef vimlop_InputIdentity_h
#define vimlop_InputIdentity_h

#include <vimlop/Results/RegistrationRecord.h>

#include <string>
#include <utility>
#include <vector>

namespace vimlop
{

/**
 * @brief Identifies one input of a run for its result folder: its path as
 * given, its size and its SHA-256. A folder (DICOM slices, frames, a COLMAP
 * model) is identified by its regular files, recursively, in the order of
 * their relative paths: the size is their total, the digest that of each
 * relative path, a NUL and the file's bytes, one after another. So the same
 * files give the same digest wherever the folder lies.
 * @throws vimlop::Error naming the path when it does not exist or a file
 * cannot be read.
 */
RegistrationRecord::InputFile identifyInput(const std::string& role, const std::string& path);

/**
 * @brief identifyInput() of each (role, path) whose path is not empty. An
 * input that cannot be identified is listed with no digest, and the reason
 * appended to `problems`: the run it describes is done, so it is a warning,
 * not a failure. Prints nothing (it may run in a thread of its own).
 */
std::vector<RegistrationRecord::InputFile> identifyInputs(
  const std::vector<std::pair<std::string, std::string>>& rolesAndPaths,
  std::vector<std::string>& problems);

/**
 * @brief The path of the record's input of `role` (e.g. "ct") when the file
 * or folder is still there; empty when the record names none or it is gone.
 */
std::string recordedInputPath(const RegistrationRecord& record, const std::string& role);

} // namespace vimlop

#endif
