#ifndef vimlop_FileError_h
#define vimlop_FileError_h

#include <vimlop/Core/Error.h>

#include <string>

namespace vimlop
{

/**
 * @brief Throws the Error of an input file: "'<path>': <problem>", the one
 * form of every reader's and checker's message, so that a user always sees
 * which file is at fault first.
 */
[[noreturn]] inline void throwFileError(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

} // namespace vimlop

#endif
