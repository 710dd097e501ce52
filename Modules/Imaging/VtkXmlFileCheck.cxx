#include <vimlop/Imaging/VtkXmlFileCheck.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Imaging/MeshFileChecks.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>

namespace vimlop::detail
{

namespace
{

/// VTK writes blocks of 32 KiB; a block larger than this is not a mesh's.
constexpr std::uint64_t maxBlockBytes = std::uint64_t(64) << 20;

/// The attributes of the tag that starts at `at` ('<'), up to its '>'.
std::map<std::string, std::string> attributesOf(const std::string& text, std::size_t at)
{
  std::map<std::string, std::string> attributes;
  const std::size_t end = text.find('>', at);
  std::size_t i = text.find_first_of(" \t\r\n", at);
  while (i < end)
  {
    const std::size_t equals = text.find('=', i);
    if (equals >= end || equals + 1 >= text.size())
    {
      break;
    }
    const std::size_t nameStart = text.find_first_not_of(" \t\r\n", i);
    const char quote = text[equals + 1];
    const std::size_t valueEnd = text.find(quote, equals + 2);
    if ((quote != '"' && quote != '\'') || valueEnd >= end)
    {
      break;
    }
    std::string name = text.substr(nameStart, equals - nameStart);
    name.erase(name.find_last_not_of(" \t\r\n") + 1);
    attributes[name] = text.substr(equals + 2, valueEnd - equals - 2);
    i = valueEnd + 1;
  }
  return attributes;
}

int base64Value(char c)
{
  if (c >= 'A' && c <= 'Z')
    return c - 'A';
  if (c >= 'a' && c <= 'z')
    return c - 'a' + 26;
  if (c >= '0' && c <= '9')
    return c - '0' + 52;
  return c == '+' ? 62 : c == '/' ? 63 : -1;
}

/// The bytes of an array's data as VTK's reader sees them: raw from `at`,
/// or decoded from the base64 text at `at` (whitespace skipped, up to the
/// first character that is not base64).
class ArrayBytes
{
public:
  ArrayBytes(const std::string& text, std::size_t at, std::size_t end, bool base64)
    : Text(text)
    , At(at)
    , End(end)
    , Base64(base64)
  {
  }

  /// The next `count` bytes, false when the data has fewer.
  bool read(std::size_t count, std::string& into)
  {
    into.clear();
    while (into.size() < count)
    {
      if (!this->Base64)
      {
        if (this->At >= this->End)
        {
          return false;
        }
        into.push_back(this->Text[this->At++]);
        continue;
      }
      if (this->Decoded.empty() && !this->decodeQuad())
      {
        return false;
      }
      into.push_back(this->Decoded.front());
      this->Decoded.erase(0, 1);
    }
    return true;
  }

  /// The bytes left (decoded size, for base64), an upper bound.
  std::uint64_t left() const
  {
    const std::uint64_t raw = this->End > this->At ? this->End - this->At : 0;
    return this->Base64 ? raw / 4 * 3 + 3 : raw;
  }

private:
  bool decodeQuad()
  {
    int values[4];
    int n = 0;
    while (n < 4 && this->At < this->End)
    {
      const char c = this->Text[this->At];
      if (c == ' ' || c == '\n' || c == '\r' || c == '\t')
      {
        ++this->At;
        continue;
      }
      if (c == '=')
      {
        ++this->At;
        values[n++] = -2;
        continue;
      }
      const int v = base64Value(c);
      if (v < 0)
      {
        break;
      }
      values[n++] = v;
      ++this->At;
    }
    if (n < 4 || values[0] < 0 || values[1] < 0)
    {
      return false;
    }
    this->Decoded.push_back(static_cast<char>(values[0] << 2 | values[1] >> 4));
    if (values[2] >= 0)
    {
      this->Decoded.push_back(static_cast<char>((values[1] & 15) << 4 | values[2] >> 2));
      if (values[3] >= 0)
      {
        this->Decoded.push_back(static_cast<char>((values[2] & 3) << 6 | values[3]));
      }
    }
    return !this->Decoded.empty();
  }

  const std::string& Text;
  std::size_t At;
  std::size_t End;
  bool Base64;
  std::string Decoded;
};

std::uint64_t number(const std::string& bytes, std::size_t at, std::size_t size, bool bigEndian)
{
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < size; ++i)
  {
    const std::size_t byte = bigEndian ? at + i : at + size - 1 - i;
    value = value << 8 | static_cast<unsigned char>(bytes[byte]);
  }
  return value;
}

} // namespace

/// VTK XML: the counts in the attributes of the Piece elements.
void checkXmlPolyData(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  for (const char* attribute : { "NumberOfPoints=\"", "NumberOfVerts=\"", "NumberOfLines=\"",
         "NumberOfStrips=\"", "NumberOfPolys=\"" })
  {
    for (size_t at = head.find(attribute); at != std::string::npos;
         at = head.find(attribute, at + 1))
    {
      const size_t digits = at + std::strlen(attribute);
      std::uint64_t count = 0;
      size_t i = digits;
      for (;
           i < head.size() && i < digits + 19 && std::isdigit(static_cast<unsigned char>(head[i]));
           ++i)
      {
        count = count * 10 + static_cast<std::uint64_t>(head[i] - '0');
      }
      const std::string name(attribute + 8, std::strlen(attribute) - 10);
      checkPromise(path, count, name == "Points" ? "points" : "cells (" + name + ")");
    }
  }
}

void checkXmlArrays(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t fileTag = text.find("<VTKFile");
  if (fileTag == std::string::npos)
  {
    return; // VTK's reader refuses it itself
  }
  std::map<std::string, std::string> file = attributesOf(text, fileTag);
  const std::string headerType = file.count("header_type") ? file["header_type"] : "UInt32";
  if (headerType != "UInt32" && headerType != "UInt64")
  {
    throwFileError(
      path, "the VTK XML header type '" + headerType + "' is neither UInt32 nor UInt64");
  }
  const std::size_t headerBytes = headerType == "UInt64" ? 8 : 4;
  const bool bigEndian = file["byte_order"] == "BigEndian";
  const bool compressed = !file["compressor"].empty();
  // Appended data starts after the '_' that follows its tag.
  const std::size_t appendedTag = text.find("<AppendedData");
  std::size_t appended = std::string::npos;
  bool appendedBase64 = false;
  if (appendedTag != std::string::npos)
  {
    appendedBase64 = attributesOf(text, appendedTag)["encoding"] != "raw";
    appended = text.find('_', text.find('>', appendedTag));
    appended = appended == std::string::npos ? appended : appended + 1;
  }
  int index = 0;
  for (std::size_t at = text.find("<DataArray"); at != std::string::npos && at < appendedTag;
       at = text.find("<DataArray", at + 1), ++index)
  {
    std::map<std::string, std::string> array = attributesOf(text, at);
    const std::string& format = array["format"];
    if (format != "binary" && format != "appended")
    {
      continue; // ascii: read as numbers, counted by the Piece checks
    }
    const std::string name = "array " + std::to_string(index) +
      (array["Name"].empty() ? std::string() : " ('" + array["Name"] + "')");
    std::size_t start = 0;
    std::size_t end = text.size();
    bool base64 = true;
    if (format == "binary")
    {
      start = text.find('>', at);
      start = start == std::string::npos ? text.size() : start + 1;
      end = std::min(end, text.find('<', start));
    }
    else
    {
      const std::string& offset = array["offset"];
      const bool digits = !offset.empty() && offset.size() <= 18 &&
        offset.find_first_not_of("0123456789") == std::string::npos;
      if (appended == std::string::npos || !digits || std::stoull(offset) > text.size() - appended)
      {
        throwFileError(
          path, "the VTK XML " + name + " has no appended data at its offset '" + offset + "'");
      }
      start = appended + static_cast<std::size_t>(std::stoull(offset));
      base64 = appendedBase64;
    }
    ArrayBytes bytes(text, start, end, base64);
    std::string header;
    const std::string cut = "the VTK XML " + name + " is cut off in its header";
    if (!compressed)
    {
      if (!bytes.read(headerBytes, header))
      {
        throwFileError(path, cut);
      }
      const std::uint64_t size = number(header, 0, headerBytes, bigEndian);
      if (size > bytes.left())
      {
        throwFileError(path,
          "the VTK XML " + name + " declares " + std::to_string(size) + " bytes and " +
            std::to_string(bytes.left()) + " are left");
      }
      continue;
    }
    // Compressed: block count, block size, last block's size, then the
    // compressed size of every block.
    if (!bytes.read(3 * headerBytes, header))
    {
      throwFileError(path, cut);
    }
    const std::uint64_t blocks = number(header, 0, headerBytes, bigEndian);
    const std::uint64_t blockSize = number(header, headerBytes, headerBytes, bigEndian);
    const std::uint64_t lastSize = number(header, 2 * headerBytes, headerBytes, bigEndian);
    if (blocks > bytes.left() / headerBytes)
    {
      throwFileError(path,
        "the VTK XML " + name + " declares " + std::to_string(blocks) +
          " compressed blocks, more than its " + std::to_string(bytes.left()) + " bytes can list");
    }
    if (blockSize > maxBlockBytes || lastSize > blockSize)
    {
      throwFileError(path,
        "the VTK XML " + name + " declares blocks of " + std::to_string(blockSize) +
          " bytes (the last of " + std::to_string(lastSize) + "); blocks of at most " +
          std::to_string(maxBlockBytes) + " bytes are read");
    }
    std::string sizes;
    if (!bytes.read(static_cast<std::size_t>(blocks * headerBytes), sizes))
    {
      throwFileError(path, cut);
    }
    std::uint64_t total = 0;
    for (std::uint64_t b = 0; b < blocks; ++b)
    {
      total += number(sizes, static_cast<std::size_t>(b * headerBytes), headerBytes, bigEndian);
      if (total > bytes.left())
      {
        throwFileError(path,
          "the VTK XML " + name + " declares " + std::to_string(total) +
            " compressed bytes or more and " + std::to_string(bytes.left()) + " are left");
      }
    }
  }
}

} // namespace vimlop::detail
