#ifndef vimlop_FuzzTemporaryFile_h
#define vimlop_FuzzTemporaryFile_h

// The parsers VIMLOP fuzzes read files by path, as users call them; each
// input is written to one temporary file per process and overwritten.

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <unistd.h>

namespace vimlop::fuzzing
{

inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& suffix)
{
  static const std::string path = "/tmp/vimlop-fuzz-" + std::to_string(getpid()) + suffix;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

} // namespace vimlop::fuzzing

#endif
