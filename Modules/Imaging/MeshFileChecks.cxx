#include <vimlop/Imaging/MeshFileChecks.h>

#include <vimlop/Core/FileError.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

namespace vimlop::detail
{

namespace
{

} // namespace

void checkPromise(const std::string& path, std::uint64_t count, const std::string& what)
{
  if (count > maxMeshElements)
  {
    throwFileError(path,
      "the file promises " + std::to_string(count) + " " + what + "; meshes with more than " +
        std::to_string(maxMeshElements) + " are refused");
  }
}

/// VTK's STL reader accepts a binary file shorter than its triangle count
/// says; check the count against the size first (binary STL: an 80-byte
/// header, a 4-byte count, 50 bytes per triangle).
void checkStl(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char start[84] = {};
  in.read(start, sizeof(start));
  const std::streamsize got = in.gcount();
  const std::uint64_t size = std::filesystem::file_size(path);
  if (got < 84)
  {
    if (got >= 5 && std::strncmp(start, "solid", 5) == 0)
    {
      return; // a short ASCII file: VTK's reader judges it
    }
    throwFileError(path, "not an STL file (too short)");
  }
  std::uint32_t count = 0;
  for (int i = 3; i >= 0; --i)
  {
    count = count << 8 | static_cast<unsigned char>(start[80 + i]);
  }
  const std::uint64_t binarySize = 84 + 50 * static_cast<std::uint64_t>(count);
  // ASCII STL starts with "solid", but so may a binary file's free header:
  // VTK's reader takes a file with non-text bytes near its start for binary
  // and allocates what its count says.
  char head[256] = {};
  in.seekg(0);
  in.read(head, sizeof(head));
  const bool text = std::all_of(head, head + in.gcount(),
    [](char c)
    {
      return std::isprint(static_cast<unsigned char>(c)) ||
        std::isspace(static_cast<unsigned char>(c));
    });
  if (binarySize == size || (std::strncmp(start, "solid", 5) == 0 && text))
  {
    return; // a consistent binary file, or ASCII
  }
  throwFileError(path,
    "truncated or corrupt binary STL (" + std::to_string(count) + " triangles need " +
      std::to_string(binarySize) + " bytes, the file has " + std::to_string(size) + ")");
}

void checkObj(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  // Vertices, texture coordinates and normals defined so far: a face's
  // indices (1-based, or negative from the latest) must name one of them.
  std::uint64_t defined[3] = { 0, 0, 0 };
  std::string line;
  for (std::uint64_t number = 1; std::getline(in, line); ++number)
  {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "v" || keyword == "vt" || keyword == "vn")
    {
      // As many numbers as VTK's reader takes (x y z; u [v [w]]; x y z).
      int numbers = 0;
      for (double value = 0.0; words >> value;)
      {
        ++numbers;
      }
      const bool enough = keyword == "vt" ? numbers >= 1 : numbers >= 3;
      if (!enough || !words.eof())
      {
        throwFileError(path,
          "line " + std::to_string(number) + " is a '" + keyword + "' line without its numbers");
      }
      ++defined[keyword == "v" ? 0 : keyword == "vt" ? 1 : 2];
      checkPromise(path, defined[0] + defined[1] + defined[2], "vertices and attributes");
      continue;
    }
    if (keyword != "f" && keyword != "l" && keyword != "p")
    {
      continue;
    }
    std::string corner;
    while (words >> corner)
    {
      // VTK's reader takes a file with normals (or texture coordinates) to
      // give them at every corner, and looked them up out of bounds otherwise.
      const std::size_t slashes = std::count(corner.begin(), corner.end(), '/');
      const bool hasTexture = slashes >= 1 && corner.find("//") == std::string::npos;
      const bool hasNormal = slashes == 2;
      if (keyword == "f" && ((defined[1] > 0 && !hasTexture) || (defined[2] > 0 && !hasNormal)))
      {
        throwFileError(path,
          "line " + std::to_string(number) + " has a corner '" + corner.substr(0, 20) +
            "' without the texture coordinate or normal the file defines for every corner");
      }
      // v, v/vt, v//vn or v/vt/vn
      std::size_t start = 0;
      for (int part = 0; part < 3 && start <= corner.size(); ++part)
      {
        const std::size_t slash = std::min(corner.find('/', start), corner.size());
        const std::string index = corner.substr(start, slash - start);
        start = slash + 1;
        // Only v//vn leaves an index empty; VTK's reader took "1/" for a
        // corner with a texture coordinate and read a null array for it.
        if (index.empty() && part == 1 && slash < corner.size())
        {
          continue;
        }
        if (index.empty() && part > 0)
        {
          throwFileError(path,
            "line " + std::to_string(number) + " has a corner '" + corner.substr(0, 20) +
              "' that ends with '/'");
        }
        char* end = nullptr;
        const long long value = std::strtoll(index.c_str(), &end, 10);
        const long long count = static_cast<long long>(defined[part]);
        if (index.empty() || *end != '\0' || value == 0 || value > count || value < -count)
        {
          static const char* const kinds[] = { "vertex", "texture coordinate", "normal" };
          throwFileError(path,
            "line " + std::to_string(number) + " names " + kinds[part] + " '" +
              index.substr(0, 20) + "'; " + std::to_string(count) + " are defined before it");
        }
        if (slash == corner.size())
        {
          break;
        }
      }
    }
  }
}

} // namespace vimlop::detail
