#ifndef vimlop_FuzzTemporaryFile_h
#define vimlop_FuzzTemporaryFile_h

// The parsers VIMLOP fuzzes read files by path, as users call them; each
// input is written to a temporary file (one per process and suffix) and
// overwritten by the next input. Readers of folders (COLMAP models, result
// folders) get one folder per process whose files are rewritten.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>
#include <vector>

namespace vimlop::fuzzing
{

/// The path of the temporary file for `suffix` in this process.
inline std::string temporaryPath(const std::string& suffix)
{
  return "/tmp/vimlop-fuzz-" + std::to_string(getpid()) + suffix;
}

inline void writeFile(const std::string& path, std::string_view bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Writes the input to this process's temporary file with `suffix` (the
/// suffix picks the format in readers that look at it).
inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& suffix)
{
  const std::string path = temporaryPath(suffix);
  writeFile(path, std::string_view(reinterpret_cast<const char*>(data), size));
  return path;
}

/// A folder of this process for readers of folders, created on first use.
inline std::string temporaryFolder(const std::string& name)
{
  const std::string path = temporaryPath("-" + name);
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  return path;
}

/**
 * The folder `name` of this process, emptied: readers of folders (DICOM
 * series, frame folders) see only the files of the current input.
 */
inline std::string emptyFolder(const std::string& name)
{
  const std::string path = temporaryPath("-" + name);
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
  std::filesystem::create_directories(path, ec);
  return path;
}

/**
 * Splits an input into `count` files at the separator line "=====\n": the
 * seed corpora hold several files of a folder in one input this way, and
 * libFuzzer's mutations (which insert and erase bytes) move data between them.
 * Missing parts are empty.
 */
inline std::vector<std::string_view> splitParts(
  const std::uint8_t* data, std::size_t size, std::size_t count)
{
  static constexpr std::string_view separator = "=====\n";
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  std::vector<std::string_view> parts;
  while (parts.size() + 1 < count)
  {
    const std::size_t at = rest.find(separator);
    if (at == std::string_view::npos)
    {
      break;
    }
    parts.push_back(rest.substr(0, at));
    rest.remove_prefix(at + separator.size());
  }
  parts.push_back(rest);
  parts.resize(count);
  return parts;
}

} // namespace vimlop::fuzzing

#endif
