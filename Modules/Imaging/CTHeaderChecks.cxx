#include <vimlop/Imaging/CTHeaderChecks.h>

#include <vimlop/Core/Error.h>

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
#include <sstream>

#include <zlib.h>

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
    fail(path, "not a NIfTI-1 or NIfTI-2 header (it does not start with its size, 348 or 540)");
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
    fail(path, "the header's vox_offset is not a byte offset in the file");
  }
  const std::uint64_t expected =
    static_cast<std::uint64_t>(std::max(voxOffset, static_cast<double>(headerBytes))) + voxelBytes;
  std::error_code ec;
  const std::uint64_t actual = std::filesystem::file_size(path, ec);
  if (!ec && actual < expected)
  {
    fail(path,
      "the file is truncated (" + std::to_string(actual) + " bytes, the header promises " +
        std::to_string(expected) + ")");
  }
}

void checkNiftiHeader(const std::string& path)
{
  // gzread reads plain and gzip-compressed files alike.
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file)
  {
    return; // ITK says what it cannot open
  }
  unsigned char header[348] = {};
  const int got = gzread(file, header, sizeof(header));
  gzclose(file);
  std::uint32_t size = 0;
  std::memcpy(&size, header, 4);
  // NIfTI-1 starts with 348, NIfTI-2 with 540 (the header's size), in the
  // file's byte order; ITK guessed at anything else and aborted on some.
  const auto is = [&](std::uint32_t v) { return size == v || __builtin_bswap32(size) == v; };
  if (got < 4 || !(is(348) || is(540)))
  {
    fail(path, "not a NIfTI-1 or NIfTI-2 header (it does not start with its size, 348 or 540)");
  }
  if (!is(348) || got < static_cast<int>(sizeof(header)))
  {
    return; // NIfTI-2 (or too short): ITK judges the rest
  }
  const bool swapped = size != 348;
  // pixdim[8] at 76, quatern_b ... qoffset_z at 256, srow_x/y/z at 280:
  // ITK takes an SVD of the orientation they make, which aborts on a NaN.
  // Bounded as well: ITK's SVD of an orientation of 1e38s did not return.
  const auto within = [&](int from, int count, float limit)
  {
    for (int i = 0; i < count; ++i)
    {
      std::uint32_t bits = 0;
      std::memcpy(&bits, header + from + 4 * i, 4);
      if (swapped)
      {
        bits = __builtin_bswap32(bits);
      }
      float v = 0.0f;
      std::memcpy(&v, &bits, 4);
      if (!(std::abs(v) <= limit))
      {
        return false;
      }
    }
    return true;
  };
  // pixdim up to 1e4 mm, quatern_b/c/d unit, offsets and sform within 1 km.
  if (!within(76, 8, 1e4f) || !within(256, 3, 1.001f) || !within(268, 3, 1e6f) ||
    !within(280, 12, 1e6f))
  {
    fail(path,
      "the header's voxel sizes or orientation (pixdim, qform, sform) are not finite or not "
      "those of a scan");
  }
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
    fail(path,
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
  for (int lines = 0; lines < 200 && std::getline(in, line); ++lines)
  {
    // MetaIO reads a key up to a NUL byte, so "ElementDataFile\0..." was its
    // data file while this reading passed it by: header text is text.
    if (!std::all_of(line.begin(), line.end(),
          [](unsigned char c) { return std::isprint(c) || c == '\t' || c == '\r'; }))
    {
      fail(path, "header line " + std::to_string(lines + 1) + " holds bytes that are not text");
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
      fail(path,
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
        fail(path,
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
    if (key != "ElementDataFile")
    {
      continue;
    }
    if (value.empty() ||
      !std::all_of(value.begin(), value.end(), [](unsigned char c) { return std::isprint(c); }))
    {
      // MetaIO read such a value as a file it could not open, then tried to
      // allocate the rest of a stream that had failed: 2^63 bytes.
      fail(path, "the header's ElementDataFile is not a file name or LOCAL");
    }
    if (value.rfind("LIST", 0) == 0 || value.find('%') != std::string::npos)
    {
      // MetaIO divided by a step of 0 read from such a pattern; a CT comes in one file.
      fail(path,
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
    if (compressed && !ec)
    {
      checkCompressedBound(path, available, voxelBytes);
      if (compressedBytes > available)
      {
        fail(path,
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
    fail(path,
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

namespace
{

/// The data elements of a DICOM file, walked as GDCM will read them, with
/// every declared length checked against the bytes its container has left:
/// GDCM allocates a length before it reads the value.
class DicomWalk
{
public:
  DicomWalk(const std::string& path, const std::string& data)
    : Path(path)
    , Data(data)
  {
  }

  /// The file meta group (explicit VR little endian) from byte 132; returns
  /// where the data set starts and whether it is implicit VR.
  std::size_t metaGroup(bool& implicit)
  {
    std::size_t at = 132;
    std::size_t groupEnd = 0; // from the group length (0002,0000)
    implicit = false;
    // The standard requires the group to start with its length; GDCM reads a
    // group without it in a compatibility mode that asserted on what followed.
    if (at + 12 <= this->Data.size() && this->u16(at) == 0x0002 &&
      (this->u16(at + 2) != 0x0000 || this->Data.compare(at + 4, 2, "UL") != 0 ||
        this->u16(at + 6) != 4))
    {
      this->corrupt(at, "starts the file meta group where its group length (0002,0000) should");
    }
    for (int elements = 0; at + 8 <= this->Data.size() && this->u16(at) == 0x0002; ++elements)
    {
      if (elements >= 100)
      {
        this->corrupt(at, "is one of more than 100 in the file meta group");
      }
      // GDCM asserts on a meta element whose VR is not the standard's.
      static const std::pair<std::uint32_t, const char*> metaVrs[] = { { 0x0000, "UL" },
        { 0x0001, "OB" }, { 0x0002, "UI" }, { 0x0003, "UI" }, { 0x0010, "UI" }, { 0x0012, "UI" },
        { 0x0013, "SH" }, { 0x0016, "AE" }, { 0x0100, "UI" }, { 0x0102, "OB" } };
      for (const auto& [element, vr] : metaVrs)
      {
        if (this->u16(at + 2) == element && this->Data.compare(at + 4, 2, vr) != 0)
        {
          this->corrupt(at,
            "has the value representation '" + this->Data.substr(at + 4, 2) +
              "' where the standard has " + vr);
        }
      }
      // Past (0002,0000), the elements must end where its group length says.
      const std::size_t value =
        this->explicitElement(at, groupEnd == 0 ? this->Data.size() : groupEnd);
      const std::uint64_t length = this->Length;
      if (this->u16(at + 2) == 0x0000 && length == 4 && groupEnd == 0)
      {
        groupEnd = value + 4 + static_cast<std::size_t>(this->u32(value));
        if (groupEnd > this->Data.size())
        {
          // GDCM read the missing group and asserted on what it found.
          fail(this->Path,
            "the file is truncated: its file meta group declares " +
              std::to_string(this->u32(value)) + " bytes and " +
              std::to_string(this->Data.size() - value - 4) + " are left");
        }
      }
      if (this->u16(at + 2) == 0x0010)
      {
        // Transfer syntax: implicit VR little endian is 1.2.840.10008.1.2 exactly.
        std::string uid = this->Data.substr(value, static_cast<std::size_t>(length));
        while (!uid.empty() && (uid.back() == '\0' || uid.back() == ' '))
        {
          uid.pop_back();
        }
        implicit = uid == "1.2.840.10008.1.2";
      }
      at = value + static_cast<std::size_t>(length);
    }
    if (at == 132)
    {
      // GDCM's reading of a file without one asserted on what it found instead.
      fail(this->Path, "the DICOM file has no file meta information group (0002) after 'DICM'");
    }
    if (groupEnd != 0 && at != groupEnd)
    {
      this->corrupt(at, "does not end the file meta group where its group length says");
    }
    return at;
  }

  /// Elements from `at` to `end` (or to a delimiter when `end` is undefined).
  std::size_t elements(std::size_t at, std::size_t end, bool implicit, int depth)
  {
    if (depth > 16)
    {
      this->corrupt(at, "lies in sequences nested more than 16 deep");
    }
    while (at + 8 <= end)
    {
      const std::uint32_t group = this->u16(at);
      const std::uint32_t element = this->u16(at + 2);
      if (group == 0xFFFE)
      {
        return at; // an item or delimiter: the caller's
      }
      const bool isImplicit = implicit;
      const std::size_t value =
        isImplicit ? this->implicitElement(at, end) : this->explicitElement(at, end);
      if (this->Length == Undefined)
      {
        // A sequence (or encapsulated pixel data) of items up to its delimiter.
        at = this->items(value, end, implicit, depth + 1);
        continue;
      }
      // GDCM asserts when an image attribute it reads as one number has
      // another length: Samples per Pixel, Rows, Columns, Bits Allocated,
      // Bits Stored, High Bit, Pixel Representation, Planar Configuration.
      static const std::uint32_t oneUS[] = { 0x0002, 0x0006, 0x0010, 0x0011, 0x0100, 0x0101, 0x0102,
        0x0103 };
      const bool imageNumber = group == 0x0028 &&
        std::find(std::begin(oneUS), std::end(oneUS), element) != std::end(oneUS);
      if (imageNumber && !isImplicit && this->Vr != "US")
      {
        this->corrupt(
          at, "has the value representation '" + this->Vr + "' where the standard has US");
      }
      if (imageNumber && this->Length != 2)
      {
        this->corrupt(
          at, "holds " + std::to_string(this->Length) + " bytes where one 16-bit number belongs");
      }
      if (!isImplicit && this->Length % this->ValueSize != 0)
      {
        this->corrupt(
          at, "holds " + std::to_string(this->Length) + " bytes, no whole number of its values");
      }
      if (this->IsSequence)
      {
        this->items(value, value + static_cast<std::size_t>(this->Length), implicit, depth + 1);
      }
      at = value + static_cast<std::size_t>(this->Length);
    }
    this->leftover(at, end);
    return at;
  }

private:
  static constexpr std::uint64_t Undefined = 0xFFFFFFFFu;

  std::uint32_t u16(std::size_t at) const
  {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(this->Data[at])) |
      static_cast<std::uint32_t>(static_cast<unsigned char>(this->Data[at + 1])) << 8;
  }

  std::uint64_t u32(std::size_t at) const
  {
    return this->u16(at) | static_cast<std::uint64_t>(this->u16(at + 2)) << 16;
  }

  [[noreturn]] void corrupt(std::size_t at, const std::string& problem) const
  {
    char tag[16] = "";
    if (at + 4 <= this->Data.size())
    {
      std::snprintf(tag, sizeof(tag), " (%04X,%04X)", this->u16(at), this->u16(at + 2));
    }
    fail(this->Path,
      "the DICOM file is corrupt: element" + std::string(tag) + " at byte " + std::to_string(at) +
        " " + problem);
  }

  void bound(std::size_t at, std::size_t value, std::size_t end) const
  {
    if (this->Length == Undefined || (value <= end && this->Length <= end - value))
    {
      return;
    }
    const std::string left = std::to_string(end > value ? end - value : 0);
    if (end == this->Data.size())
    {
      char tag[16];
      std::snprintf(tag, sizeof(tag), "(%04X,%04X)", this->u16(at), this->u16(at + 2));
      fail(this->Path,
        "the file is truncated: element " + std::string(tag) + " at byte " + std::to_string(at) +
          " declares " + std::to_string(this->Length) + " bytes and " + left + " are left");
    }
    this->corrupt(at,
      "declares " + std::to_string(this->Length) + " bytes, more than the " + left +
        " left in the group or sequence around it");
  }

  std::size_t explicitElement(std::size_t at, std::size_t end)
  {
    static const char* const vrs[] = { "AE", "AS", "AT", "CS", "DA", "DS", "DT", "FL", "FD", "IS",
      "LO", "LT", "OB", "OD", "OF", "OL", "OV", "OW", "PN", "SH", "SL", "SQ", "SS", "ST", "SV",
      "TM", "UC", "UI", "UL", "UN", "UR", "US", "UT", "UV" };
    static const char* const longVrs[] = { "OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC",
      "UN", "UR", "UT", "UV" };
    const std::string vr = this->Data.substr(at + 4, 2);
    const auto in = [&](const char* const* list, std::size_t n)
    { return std::find_if(list, list + n, [&](const char* v) { return vr == v; }) != list + n; };
    if (!in(vrs, std::size(vrs)))
    {
      this->corrupt(at, "has no valid value representation");
    }
    this->IsSequence = vr == "SQ";
    this->Vr = vr;
    this->ValueSize = vr == "US" || vr == "SS" || vr == "OW"                             ? 2
      : vr == "UL" || vr == "SL" || vr == "FL" || vr == "AT" || vr == "OF" || vr == "OL" ? 4
      : vr == "FD" || vr == "OD" || vr == "SV" || vr == "UV" || vr == "OV"               ? 8
                                                                                         : 1;
    std::size_t value = 0;
    if (in(longVrs, std::size(longVrs)))
    {
      if (at + 12 > end)
      {
        this->corrupt(at, "is cut off");
      }
      this->Length = this->u32(at + 8);
      value = at + 12;
    }
    else
    {
      this->Length = this->u16(at + 6);
      value = at + 8;
    }
    this->bound(at, value, end);
    return value;
  }

  std::size_t implicitElement(std::size_t at, std::size_t end)
  {
    this->IsSequence = false; // not known without a dictionary: a defined length is skipped whole
    this->ValueSize = 1;
    this->Length = this->u32(at + 4);
    this->bound(at, at + 8, end);
    return at + 8;
  }

  /// Items (FFFE,E000) up to `end` or a sequence delimiter (FFFE,E0DD).
  std::size_t items(std::size_t at, std::size_t end, bool implicit, int depth)
  {
    while (at + 8 <= end)
    {
      if (this->u16(at) != 0xFFFE)
      {
        this->corrupt(at, "stands where a sequence item should");
      }
      const std::uint32_t kind = this->u16(at + 2);
      this->Length = this->u32(at + 4);
      if (kind == 0xE0DD)
      {
        return at + 8;
      }
      if (kind != 0xE000)
      {
        this->corrupt(at, "is no sequence item");
      }
      const std::size_t value = at + 8;
      if (this->Length == Undefined)
      {
        at = this->elements(value, end, implicit, depth);
        if (at + 8 > end || this->u16(at) != 0xFFFE || this->u16(at + 2) != 0xE00D)
        {
          this->corrupt(at < end ? at : value, "ends an item without its delimiter");
        }
        at += 8;
        continue;
      }
      this->bound(at, value, end);
      // A fragment of pixel data or an item's elements: both are bounded.
      at = value + static_cast<std::size_t>(this->Length);
    }
    this->leftover(at, end);
    return at;
  }

  /// Fewer bytes than an element header left at the end of a container:
  /// GDCM reads them as a tag and a VR and aborts on what it finds.
  void leftover(std::size_t at, std::size_t end) const
  {
    if (at >= end)
    {
      return;
    }
    if (end == this->Data.size())
    {
      fail(this->Path,
        "the file is truncated: it ends inside an element at byte " + std::to_string(at));
    }
    fail(this->Path,
      "the DICOM file is corrupt: a sequence ends inside an element at byte " + std::to_string(at));
  }

  const std::string& Path;
  const std::string& Data;
  std::uint64_t Length = 0;
  bool IsSequence = false;
  std::uint64_t ValueSize = 1; ///< bytes of one value of the element's VR (1: text or bytes)
  std::string Vr;              ///< of the last explicit-VR element
};

} // namespace

bool hasDicomPreamble(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char head[132] = {};
  in.read(head, sizeof(head));
  return in.gcount() == 132 && std::memcmp(head + 128, "DICM", 4) == 0;
}

void checkDicomPart10(const std::string& path)
{
  if (!hasDicomPreamble(path))
  {
    fail(path, "not a DICOM file (no 'DICM' at byte 128)");
  }
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  DicomWalk walk(path, data);
  bool implicit = false;
  const std::size_t dataSet = walk.metaGroup(implicit);
  walk.elements(dataSet, data.size(), implicit, 0);
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
    fail(path, problem.str());
  }
}

} // namespace vimlop::detail
