#ifndef vimlop_AtomicFile_h
#define vimlop_AtomicFile_h

#include <string>

namespace vimlop
{

/**
 * @brief Writes `contents` to `path` through a temporary file beside it
 * (`path` + ".part") and a rename, so an interrupted run leaves either the
 * old file or the complete new one, never a half-written file. A missing
 * parent folder is created; an existing file is replaced.
 * @throws vimlop::Error "'path': cannot write the file" when the temporary
 * file cannot be written, with the system's reason in parentheses when the
 * rename fails; the temporary file is removed in both cases.
 */
void writeFileAtomically(const std::string& path, const std::string& contents);

} // namespace vimlop

#endif
