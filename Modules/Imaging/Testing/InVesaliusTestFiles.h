#ifndef vimlop_InVesaliusTestFiles_h
#define vimlop_InVesaliusTestFiles_h

// Writes small InVesalius-like projects (gzip tar + main.plist + matrix.dat)
// so the reader can be tested without the real data and with broken variants.

#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace vimlop::fixtures
{

inline std::string tarMember(const std::string& name, const std::string& content)
{
  char header[512] = {};
  std::snprintf(header, 100, "%s", name.c_str());
  std::snprintf(header + 100, 8, "%07o", 0644);
  std::snprintf(header + 124, 12, "%011o", static_cast<unsigned>(content.size()));
  header[156] = '0';
  std::memcpy(header + 257, "ustar", 5);
  std::memset(header + 148, ' ', 8);
  unsigned sum = 0;
  for (unsigned char c : header)
  {
    sum += c;
  }
  std::snprintf(header + 148, 8, "%06o", sum);
  std::string out(header, 512);
  out += content;
  out.append((512 - content.size() % 512) % 512, '\0');
  return out;
}

inline std::string plist(int nx, int ny, int nz, const std::string& dtype = "int16",
  const std::string& spacing = "<real>0.5</real><real>0.75</real><real>2.0</real>")
{
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<plist version=\"1.0\"><dict>"
         "<key>matrix</key><dict><key>dtype</key><string>" +
    dtype +
    "</string><key>filename</key><string>matrix.dat</string>"
    "<key>shape</key><array><integer>" +
    std::to_string(nz) + "</integer><integer>" + std::to_string(ny) + "</integer><integer>" +
    std::to_string(nx) + "</integer></array></dict><key>spacing</key><array>" + spacing +
    "</array></dict></plist>\n";
}

/// Voxel value at (x, y, z) in the test volumes: distinct and signed.
inline std::int16_t testVoxel(int x, int y, int z)
{
  return static_cast<std::int16_t>(100 * z + 10 * y + x - 500);
}

inline std::string matrix(int nx, int ny, int nz)
{
  std::string raw;
  for (int z = 0; z < nz; ++z)
  {
    for (int y = 0; y < ny; ++y)
    {
      for (int x = 0; x < nx; ++x)
      {
        const auto v = static_cast<std::uint16_t>(testVoxel(x, y, z));
        raw.push_back(static_cast<char>(v & 0xff));
        raw.push_back(static_cast<char>(v >> 8));
      }
    }
  }
  return raw;
}

/// Writes the members (name, content) as a gzip-compressed tar; returns the path.
inline std::string writeProject(
  const std::string& path, const std::vector<std::pair<std::string, std::string>>& members)
{
  std::string tar;
  for (const auto& [name, content] : members)
  {
    tar += tarMember(name, content);
  }
  tar.append(1024, '\0');
  gzFile file = gzopen(path.c_str(), "wb");
  gzwrite(file, tar.data(), static_cast<unsigned>(tar.size()));
  gzclose(file);
  return path;
}

} // namespace vimlop::fixtures

#endif
