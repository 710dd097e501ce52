#include <vimlop/Imaging/CTHeaderChecks.h>

#include <vimlop/Core/Error.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace vimlop::detail
{

namespace
{

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

} // namespace

/// ITK's NIfTI reader fills a short file's missing voxels silently; compare
/// the size of an uncompressed NIfTI-1 file with what its header promises.
void checkNiftiLength(const std::string& path, std::uint64_t voxelBytes)
{
  std::ifstream file(path, std::ios::binary);
  unsigned char header[112] = {};
  if (!file.read(reinterpret_cast<char*>(header), sizeof(header)))
  {
    return; // ITK has already judged the header
  }
  auto u32 = [&](int at, bool little)
  {
    return little ? std::uint32_t(header[at]) | std::uint32_t(header[at + 1]) << 8 |
        std::uint32_t(header[at + 2]) << 16 | std::uint32_t(header[at + 3]) << 24
                  : std::uint32_t(header[at + 3]) | std::uint32_t(header[at + 2]) << 8 |
        std::uint32_t(header[at + 1]) << 16 | std::uint32_t(header[at]) << 24;
  };
  bool little = true;
  if (u32(0, true) != 348)
  {
    if (u32(0, false) != 348)
    {
      return; // not NIfTI-1 (NIfTI-2 files are left to ITK)
    }
    little = false;
  }
  const std::uint32_t bits = u32(108, little);
  float voxOffset = 0.0f;
  std::memcpy(&voxOffset, &bits, sizeof(voxOffset));
  const std::uint64_t expected =
    static_cast<std::uint64_t>(std::max(voxOffset, 348.0f)) + voxelBytes;
  std::error_code ec;
  const std::uint64_t actual = std::filesystem::file_size(path, ec);
  if (!ec && actual < expected)
  {
    fail(path,
      "the file is truncated (" + std::to_string(actual) + " bytes, the header promises " +
        std::to_string(expected) + ")");
  }
}

/// A MetaImage header names its data file (or LOCAL: the data follow the
/// header). MetaIO prints to stderr when the file is missing and reads a
/// short one as zeros (0 HU), so look first and say it in one line.
void checkMetaImageData(const std::string& path, std::uint64_t voxelBytes)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  bool compressed = false;
  long long headerBytes = 0; // HeaderSize: bytes to skip in the data file; -1 reads the tail
  for (int lines = 0; lines < 200 && std::getline(in, line); ++lines)
  {
    const auto equals = line.find('=');
    if (equals == std::string::npos)
    {
      continue;
    }
    std::string key = line.substr(0, equals);
    key.erase(key.find_last_not_of(" \t") + 1);
    std::string value = line.substr(equals + 1);
    value.erase(0, value.find_first_not_of(" \t"));
    value.erase(value.find_last_not_of(" \t\r") + 1);
    if (key == "CompressedData")
    {
      compressed = value == "True" || value == "true" || value == "TRUE";
    }
    else if (key == "HeaderSize")
    {
      headerBytes = std::atoll(value.c_str());
    }
    if (key != "ElementDataFile")
    {
      continue;
    }
    if (value == "LIST" || value.find('%') != std::string::npos)
    {
      return; // one file per slice: left to MetaIO
    }
    std::error_code ec;
    std::uint64_t available = 0;
    if (value == "LOCAL")
    {
      const std::uint64_t size = std::filesystem::file_size(path, ec);
      available = size - std::min(size, static_cast<std::uint64_t>(in.tellg()));
    }
    else
    {
      const std::filesystem::path data = std::filesystem::path(path).parent_path() / value;
      if (!std::filesystem::exists(data, ec))
      {
        fail(path, "the data file '" + value + "' named by the header does not exist");
      }
      available = std::filesystem::file_size(data, ec);
      available -= std::min<std::uint64_t>(available, std::max(headerBytes, 0LL));
    }
    if (!compressed && !ec && available < voxelBytes)
    {
      fail(path,
        "the image data are cut short (" + std::to_string(available) +
          " bytes, the header promises " + std::to_string(voxelBytes) + ")");
    }
    return;
  }
}

void checkNrrdHeader(const std::string& path)
{
  constexpr std::size_t maxLine = 1024;
  // A header is text at the start of the file; 1 MiB holds any real one.
  std::ifstream in(path, std::ios::binary);
  std::string text(1 << 20, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.compare(0, 4, "NRRD") != 0)
  {
    return; // not an NRRD header: ITK judges it
  }
  bool detached = false;
  std::size_t start = 0;
  for (int number = 1; start < text.size(); ++number)
  {
    const std::size_t newline = text.find('\n', start);
    const std::size_t end = newline == std::string::npos ? text.size() : newline;
    std::string line = text.substr(start, std::min(end - start, maxLine + 1));
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    if (end - start > maxLine + 1 || line.size() > maxLine)
    {
      fail(path,
        "header line " + std::to_string(number) + " is " + std::to_string(end - start) +
          " characters long; NRRD header lines of at most " + std::to_string(maxLine) +
          " are read");
    }
    if (line.empty() && newline != std::string::npos)
    {
      return; // the blank line: the data follow
    }
    if (line.rfind("data file:", 0) == 0 || line.rfind("datafile:", 0) == 0)
    {
      detached = true;
    }
    if (newline == std::string::npos)
    {
      break;
    }
    start = newline + 1;
  }
  if (!detached)
  {
    fail(path, "the header does not end with a blank line before the data");
  }
}

} // namespace vimlop::detail
