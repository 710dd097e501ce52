#ifndef vimlop_AtomicFile_h
#define vimlop_AtomicFile_h

#include <string>

namespace vimlop
{

/**
 * @brief Flushes a file's bytes, or a folder's entries, to disk (fsync).
 * @throws vimlop::Error "'path': cannot flush it to disk (reason)".
 */
void syncToDisk(const std::string& path);

/**
 * @brief Writes `contents` to `path` through a temporary file beside it
 * (`path` + ".part"), flushed to disk, and a rename, so an interrupted run
 * or a power cut leaves either the old file or the complete new one, never a
 * half-written file. A missing
 * parent folder is created; an existing file is replaced.
 * @throws vimlop::Error "'path': cannot write the file" when the temporary
 * file cannot be written, with the system's reason in parentheses when the
 * rename fails; the temporary file is removed in both cases.
 */
void writeFileAtomically(const std::string& path, const std::string& contents);

/**
 * @brief The whole of a file, its bytes as they are (a file written by
 * writeFileAtomically() is always whole).
 * @throws vimlop::Error "'path': cannot read it (reason)".
 */
std::string readWholeFile(const std::string& path);

} // namespace vimlop

#endif
