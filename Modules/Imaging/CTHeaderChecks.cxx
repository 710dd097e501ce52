#include <vimlop/Imaging/CTHeaderChecks.h>

#include <vimlop/Core/FileError.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <set>
#include <sstream>

#include <zlib.h>

namespace vimlop::detail
{

namespace
{

} // namespace

/// ITK's NIfTI reader fills a short file's missing voxels silently; compare
/// the size of an uncompressed NIfTI-1 file with what its header promises.
void checkNiftiLength(const std::string& path, std::uint64_t voxelBytes)
{
  std::ifstream file(path, std::ios::binary);
  unsigned char header[176] = {};
  file.read(reinterpret_cast<char*>(header), sizeof(header));
  if (file.gcount() < 112)
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
  // NIfTI-1 starts with 348, NIfTI-2 with 540 (the header's size), in the
  // file's byte order; ITK reads both, and anything else it reads as such
  // was allocating what its dimensions said.
  const bool little = u32(0, true) == 348 || u32(0, true) == 540;
  const std::uint32_t headerBytes = u32(0, little);
  if (headerBytes != 348 && headerBytes != 540)
  {
    throwFileError(
      path, "not a NIfTI-1 or NIfTI-2 header (it does not start with its size, 348 or 540)");
  }
  double voxOffset = 0.0;
  if (headerBytes == 348)
  {
    const std::uint32_t bits = u32(108, little);
    float offset = 0.0f;
    std::memcpy(&offset, &bits, sizeof(offset));
    voxOffset = offset;
  }
  else if (file.gcount() >= 176)
  {
    // NIfTI-2: vox_offset is a 64-bit integer at byte 168.
    const std::uint64_t low = u32(little ? 168 : 172, little);
    const std::uint64_t high = u32(little ? 172 : 168, little);
    voxOffset = static_cast<double>(static_cast<std::int64_t>(high << 32 | low));
  }
  if (!(voxOffset >= 0.0 && voxOffset < 1e15))
  {
    throwFileError(path, "the header's vox_offset is not a byte offset in the file");
  }
  const std::uint64_t expected =
    static_cast<std::uint64_t>(std::max(voxOffset, static_cast<double>(headerBytes))) + voxelBytes;
  std::error_code ec;
  const std::uint64_t actual = std::filesystem::file_size(path, ec);
  if (!ec && actual < expected)
  {
    throwFileError(path,
      "the file is truncated (" + std::to_string(actual) + " bytes, the header promises " +
        std::to_string(expected) + ")");
  }
}

int checkNiftiHeader(const std::string& path)
{
  // gzread reads plain and gzip-compressed files alike.
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file)
  {
    return 0; // ITK says what it cannot open
  }
  unsigned char header[540] = {};
  const int got = gzread(file, header, sizeof(header));
  gzclose(file);
  std::uint32_t size = 0;
  std::memcpy(&size, header, 4);
  // NIfTI-1 starts with 348, NIfTI-2 with 540 (the header's size), in the
  // file's byte order; ITK guessed at anything else and aborted on some.
  const auto is = [&](std::uint32_t v) { return size == v || __builtin_bswap32(size) == v; };
  if (got < 4 || !(is(348) || is(540)))
  {
    throwFileError(
      path, "not a NIfTI-1 or NIfTI-2 header (it does not start with its size, 348 or 540)");
  }
  const bool nifti2 = is(540);
  if (got < (nifti2 ? 540 : 348))
  {
    return nifti2 ? 2 : 1; // too short: ITK says so
  }
  const bool swapped = size != (nifti2 ? 540u : 348u);
  // ITK takes an SVD of the orientation, which aborts on a NaN; bounded as
  // well: ITK's SVD of an orientation of 1e38s did not return. NIfTI-1 has
  // floats, NIfTI-2 doubles, at other places.
  const auto within = [&](int from, int count, double limit)
  {
    const int bytes = nifti2 ? 8 : 4;
    for (int i = 0; i < count; ++i)
    {
      unsigned char value[8] = {};
      std::memcpy(value, header + from + bytes * i, static_cast<std::size_t>(bytes));
      if (swapped)
      {
        std::reverse(value, value + bytes);
      }
      double v = 0.0;
      if (nifti2)
      {
        std::memcpy(&v, value, 8);
      }
      else
      {
        float f = 0.0f;
        std::memcpy(&f, value, 4);
        v = f;
      }
      if (!(std::abs(v) <= limit))
      {
        return false;
      }
    }
    return true;
  };
  // pixdim[8], quatern_b/c/d, qoffset_x/y/z, srow_x/y/z: at 76, 256, 268,
  // 280 in NIfTI-1, at 104, 352, 376, 400 in NIfTI-2. pixdim up to 1e4 mm,
  // quatern_b/c/d unit, offsets and sform within 1 km.
  const int pixdim = nifti2 ? 104 : 76;
  const int quatern = nifti2 ? 352 : 256;
  const int offsets = nifti2 ? 376 : 268;
  const int srow = nifti2 ? 400 : 280;
  if (!within(pixdim, 8, 1e4) || !within(quatern, 3, 1.001) || !within(offsets, 3, 1e6) ||
    !within(srow, 12, 1e6))
  {
    throwFileError(path,
      "the header's voxel sizes or orientation (pixdim, qform, sform) are not finite or not "
      "those of a scan");
  }
  return nifti2 ? 2 : 1;
}

/// A MetaImage header names its data file (or LOCAL: the data follow the
/// header). MetaIO prints to stderr when the file is missing and reads a
/// short one as zeros (0 HU), so look first and say it in one line.
void checkCompressedBound(
  const std::string& path, std::uint64_t compressedBytes, std::uint64_t voxelBytes)
{
  // Deflate (gzip, zlib) expands a byte into at most 1032.
  constexpr std::uint64_t maxRatio = 1032;
  if (compressedBytes < voxelBytes / maxRatio)
  {
    throwFileError(path,
      "the header promises " + std::to_string(voxelBytes) + " bytes of voxels, which " +
        std::to_string(compressedBytes) +
        " bytes of compressed data cannot hold; refusing to allocate them");
  }
}

void checkMetaImageData(const std::string& path, std::uint64_t voxelBytes)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  bool compressed = false;
  long long headerBytes = 0; // HeaderSize: bytes to skip in the data file; -1 reads the tail
  std::uint64_t compressedBytes = 0;
  std::set<std::string> required = { "DimSize", "ElementType", "NDims" };
  // Every line up to ElementDataFile, as MetaIO reads them (a limit of 200
  // lines let MetaIO read on past what was checked, to a buffer overflow).
  for (int lines = 0; std::getline(in, line); ++lines)
  {
    // MetaIO reads a key up to a NUL byte, so "ElementDataFile\0..." was its
    // data file while this reading passed it by: header text is text.
    if (!std::all_of(line.begin(), line.end(),
          [](unsigned char c) { return std::isprint(c) || c == '\t' || c == '\r'; }))
    {
      throwFileError(
        path, "header line " + std::to_string(lines + 1) + " holds bytes that are not text");
    }
    const auto equals = line.find('=');
    if (equals == std::string::npos)
    {
      continue;
    }
    std::string key = line.substr(0, equals);
    key.erase(key.find_last_not_of(" \t") + 1);
    // MetaIO matches a key it does not know against its own by their start
    // ("C" became a field whose copy overflowed a buffer): only its keys.
    static const char* const keys[] = { "Comment", "ObjectType", "ObjectSubType", "NDims", "Name",
      "ID", "ParentID", "Color", "Position", "Origin", "Offset", "TransformMatrix", "Orientation",
      "Rotation", "CenterOfRotation", "AnatomicalOrientation", "ElementSpacing", "ElementSize",
      "DimSize", "HeaderSize", "HeaderSizes", "Modality", "SequenceID", "ElementMin", "ElementMax",
      "ElementNumberOfChannels", "ElementType", "ElementDataFile", "BinaryData",
      "BinaryDataByteOrderMSB", "ElementByteOrderMSB", "CompressedData", "CompressedDataSize",
      "TransformType", "AcquisitionDate", "DistanceUnits" };
    if (std::none_of(std::begin(keys), std::end(keys), [&](const char* k) { return key == k; }))
    {
      throwFileError(path,
        "header line " + std::to_string(lines + 1) + " has the key '" + key.substr(0, 40) +
          "', which MetaImage does not define");
    }
    std::string value = line.substr(equals + 1);
    value.erase(0, value.find_first_not_of(" \t"));
    value.erase(value.find_last_not_of(" \t\r") + 1);
    if (key == "NDims" || key == "ElementNumberOfChannels")
    {
      // MetaIO reads that many numbers per field: a negative count did not end.
      char* end = nullptr;
      const long count = std::strtol(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0' || count < 1 || count > (key == "NDims" ? 4 : 16))
      {
        throwFileError(path,
          "the header's " + key + " is '" + value.substr(0, 20) + "', not a count of " +
            (key == "NDims" ? "1 to 4 dimensions" : "1 to 16 channels"));
      }
    }
    if (key == "CompressedData")
    {
      compressed = value == "True" || value == "true" || value == "TRUE";
    }
    else if (key == "HeaderSize")
    {
      headerBytes = std::atoll(value.c_str());
    }
    else if (key == "CompressedDataSize")
    {
      // MetaIO allocates this many bytes before reading them.
      compressedBytes = std::strtoull(value.c_str(), nullptr, 10);
    }
    required.erase(key);
    if (key != "ElementDataFile")
    {
      continue;
    }
    if (!required.empty())
    {
      // MetaIO read on past such an ElementDataFile, into the data, and took
      // an NDims of 4444... from it (17 GB).
      throwFileError(path,
        "the header gives ElementDataFile before its " + *required.begin() +
          " (ElementDataFile is a MetaImage header's last field)");
    }
    if (value.empty() ||
      !std::all_of(value.begin(), value.end(), [](unsigned char c) { return std::isprint(c); }))
    {
      // MetaIO read such a value as a file it could not open, then tried to
      // allocate the rest of a stream that had failed: 2^63 bytes.
      throwFileError(path, "the header's ElementDataFile is not a file name or LOCAL");
    }
    if (value.rfind("LIST", 0) == 0 || value.find('%') != std::string::npos)
    {
      // MetaIO divided by a step of 0 read from such a pattern; a CT comes in one file.
      throwFileError(path,
        "the header lists one data file per slice (LIST or a pattern); VIMLOP reads MetaImage "
        "volumes whose data are in one file");
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
        throwFileError(path, "the data file '" + value + "' named by the header does not exist");
      }
      available = std::filesystem::file_size(data, ec);
      available -= std::min<std::uint64_t>(available, std::max(headerBytes, 0LL));
    }
    if (!compressed && !ec && available < voxelBytes)
    {
      throwFileError(path,
        "the image data are cut short (" + std::to_string(available) +
          " bytes, the header promises " + std::to_string(voxelBytes) + ")");
    }
    if (compressed && !ec)
    {
      checkCompressedBound(path, available, voxelBytes);
      if (compressedBytes > available)
      {
        throwFileError(path,
          "the header's CompressedDataSize (" + std::to_string(compressedBytes) +
            " bytes) is more than the " + std::to_string(available) + " bytes of data");
      }
    }
    return;
  }
}

void checkNrrdData(const std::string& path, std::uint64_t voxelBytes)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::string encoding = "raw";
  std::string dataFile;
  std::uint64_t headerEnd = 0;
  for (int lines = 0; lines < 1000 && std::getline(in, line); ++lines)
  {
    headerEnd += line.size() + 1;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    if (line.empty())
    {
      break; // attached data follow
    }
    const auto colon = line.find(": ");
    if (colon == std::string::npos)
    {
      continue;
    }
    const std::string key = line.substr(0, colon);
    const std::string value = line.substr(colon + 2);
    if (key == "encoding")
    {
      encoding = value;
    }
    else if (key == "data file" || key == "datafile")
    {
      dataFile = value;
    }
  }
  std::error_code ec;
  std::uint64_t available = 0;
  if (dataFile.empty())
  {
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    available = size - std::min(size, headerEnd);
  }
  else if (dataFile.find(' ') == std::string::npos && dataFile != "LIST")
  {
    const std::filesystem::path data = std::filesystem::path(path).parent_path() / dataFile;
    available = std::filesystem::file_size(data, ec);
  }
  else
  {
    return; // a list or pattern of files: left to teem
  }
  if (ec)
  {
    return; // teem says what is missing
  }
  if (encoding == "raw" && available < voxelBytes)
  {
    throwFileError(path,
      "the image data are cut short (" + std::to_string(available) +
        " bytes, the header promises " + std::to_string(voxelBytes) + ")");
  }
  if (encoding == "gzip" || encoding == "gz")
  {
    checkCompressedBound(path, available, voxelBytes);
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
      throwFileError(path,
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
    throwFileError(path, "the header does not end with a blank line before the data");
  }
}

/// ITK reads a spacing of 1e300 mm or an origin of 1e308 mm as given, and
/// they overflow later.
void checkGridGeometry(const std::string& path, const std::array<double, 3>& spacingMm,
  const std::array<double, 3>& originMm, const std::array<double, 9>& direction)
{
  constexpr double maxSpacingMm = 100.0;
  constexpr double maxOriginMm = 1e6;
  std::ostringstream problem;
  problem << std::setprecision(6);
  const auto& s = spacingMm;
  const auto& o = originMm;
  if (!std::all_of(s.begin(), s.end(),
        [](double v) { return std::isfinite(v) && v > 0.0 && v <= maxSpacingMm; }))
  {
    problem << "the voxel spacing " << s[0] << " x " << s[1] << " x " << s[2]
            << " mm is not a CT's: each must be finite, positive and at most " << maxSpacingMm
            << " mm";
  }
  else if (!std::all_of(o.begin(), o.end(),
             [](double v) { return std::isfinite(v) && std::abs(v) <= maxOriginMm; }))
  {
    problem << "the origin (" << o[0] << ", " << o[1] << ", " << o[2]
            << ") mm is not finite or lies farther than 1 km from the scanner's";
  }
  else
  {
    // The columns (the voxel axes in LPS) unit and perpendicular.
    const auto& d = direction;
    for (int a = 0; a < 3 && problem.str().empty(); ++a)
    {
      for (int b = a; b < 3; ++b)
      {
        const double dot = d[a] * d[b] + d[3 + a] * d[3 + b] + d[6 + a] * d[6 + b];
        if (!(std::abs(dot - (a == b ? 1.0 : 0.0)) <= 1e-3))
        {
          problem << "the direction matrix is not orthonormal (its columns, the voxel axes, must "
                     "be unit vectors at right angles)";
          break;
        }
      }
    }
  }
  if (!problem.str().empty())
  {
    throwFileError(path, problem.str());
  }
}

} // namespace vimlop::detail
