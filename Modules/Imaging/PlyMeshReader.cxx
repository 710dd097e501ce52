#include <vimlop/Imaging/PlyMeshReader.h>

#include <vimlop/Core/FileError.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace vimlop::detail
{

namespace
{

enum class PlyFormat
{
  Ascii,
  LittleEndian,
  BigEndian,
};

/// A value for a message: whole numbers without decimals.
std::string numberText(double v)
{
  if (std::abs(v) < 1e18 && v == static_cast<double>(static_cast<std::int64_t>(v)))
  {
    return std::to_string(static_cast<std::int64_t>(v));
  }
  std::ostringstream text;
  text << v;
  return text.str();
}

/// A PLY type: its size and kind; 0 bytes when unknown.
struct PlyType
{
  int bytes = 0;
  bool isFloat = false;
  bool isSigned = false;
};

PlyType typeNamed(const std::string& name)
{
  struct Named
  {
    const char* names[2];
    PlyType type;
  };
  static const Named types[] = { { { "char", "int8" }, { 1, false, true } },
    { { "uchar", "uint8" }, { 1, false, false } }, { { "short", "int16" }, { 2, false, true } },
    { { "ushort", "uint16" }, { 2, false, false } }, { { "int", "int32" }, { 4, false, true } },
    { { "uint", "uint32" }, { 4, false, false } }, { { "float", "float32" }, { 4, true, true } },
    { { "double", "float64" }, { 8, true, true } } };
  for (const Named& t : types)
  {
    if (name == t.names[0] || name == t.names[1])
    {
      return t.type;
    }
  }
  return PlyType();
}

/// A property: a scalar, or a list (a count, then that many items).
struct PlyProperty
{
  std::string name;
  PlyType type;  ///< of the scalar, or of each list item
  PlyType count; ///< of a list's count; 0 bytes for a scalar
};

struct PlyElement
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

/// The values of one element after another: bytes of a binary body, or the
/// words of one line per element of an ASCII body.
class PlyValues
{
public:
  PlyValues(const std::string& path, const std::string& data, std::size_t at, PlyFormat format)
    : Path(path)
    , Data(data)
    , At(at)
    , Format(format)
  {
  }

  /// Starts element `index` of `element` (an ASCII body reads its line).
  void start(const PlyElement& element, std::uint64_t index)
  {
    this->Where = "element '" + element.name + "' " + std::to_string(index) + " of " +
      std::to_string(element.count);
    if (this->Format != PlyFormat::Ascii)
    {
      return;
    }
    if (this->At >= this->Data.size())
    {
      throwFileError(this->Path, "the file ends before " + this->Where + " (truncated)");
    }
    const std::size_t newline = std::min(this->Data.find('\n', this->At), this->Data.size());
    this->Line.clear();
    this->Line.str(this->Data.substr(this->At, newline - this->At));
    this->At = std::min(newline + 1, this->Data.size());
  }

  double next(const PlyType& type)
  {
    if (this->Format == PlyFormat::Ascii)
    {
      double value = 0.0;
      if (!(this->Line >> value))
      {
        throwFileError(this->Path, this->Where + " has too few values");
      }
      return value;
    }
    const auto bytes = static_cast<std::size_t>(type.bytes);
    if (bytes > this->Data.size() - this->At)
    {
      throwFileError(this->Path, "the file ends inside " + this->Where + " (truncated)");
    }
    std::uint64_t bits = 0;
    for (std::size_t i = 0; i < bytes; ++i)
    {
      const std::size_t byte = this->Format == PlyFormat::BigEndian ? i : bytes - 1 - i;
      bits = bits << 8 | static_cast<unsigned char>(this->Data[this->At + byte]);
    }
    this->At += bytes;
    if (type.isFloat)
    {
      if (bytes == 4)
      {
        float f = 0.0f;
        const auto b32 = static_cast<std::uint32_t>(bits);
        std::memcpy(&f, &b32, sizeof(f));
        return f;
      }
      double d = 0.0;
      std::memcpy(&d, &bits, sizeof(d));
      return d;
    }
    if (type.isSigned && (bits >> (8 * bytes - 1)) != 0)
    {
      return static_cast<double>(
        static_cast<std::int64_t>(bits) - (std::int64_t(1) << (8 * bytes)));
    }
    return static_cast<double>(bits);
  }

  const std::string& where() const { return this->Where; }

private:
  const std::string& Path;
  const std::string& Data;
  std::size_t At;
  PlyFormat Format;
  std::string Where;
  std::istringstream Line;
};

/// The header up to end_header; `at` ends after it.
std::vector<PlyElement> readHeader(
  const std::string& path, const std::string& data, std::size_t& at, PlyFormat& format)
{
  std::vector<PlyElement> elements;
  bool hasFormat = false;
  for (int lines = 0; lines < 1000 && at < data.size(); ++lines)
  {
    const std::size_t newline = std::min(data.find('\n', at), data.size());
    std::istringstream words(data.substr(at, newline - at));
    at = std::min(newline + 1, data.size()); // a last line without a newline ends at the end
    std::string keyword;
    words >> keyword;
    if (lines == 0)
    {
      if (keyword != "ply")
      {
        throwFileError(path, "not a PLY file");
      }
      continue;
    }
    if (keyword == "end_header")
    {
      if (!hasFormat)
      {
        throwFileError(path, "not a PLY file (no format line)");
      }
      return elements;
    }
    if (keyword == "format")
    {
      std::string name;
      words >> name;
      hasFormat = true;
      if (name == "ascii")
      {
        format = PlyFormat::Ascii;
      }
      else if (name == "binary_little_endian")
      {
        format = PlyFormat::LittleEndian;
      }
      else if (name == "binary_big_endian")
      {
        format = PlyFormat::BigEndian;
      }
      else
      {
        throwFileError(path, "unknown PLY format '" + name.substr(0, 40) + "'");
      }
    }
    else if (keyword == "element")
    {
      PlyElement element;
      if (!(words >> element.name >> element.count))
      {
        throwFileError(path, "a PLY element line without a name and a count");
      }
      // Each element takes at least one byte: a larger count is a lie.
      if (element.count > data.size())
      {
        throwFileError(path,
          "the PLY header promises " + std::to_string(element.count) + " " + element.name +
            " elements in a " + std::to_string(data.size()) + "-byte file");
      }
      elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (elements.empty())
      {
        throwFileError(path, "a PLY property before any element");
      }
      PlyProperty property;
      std::string type;
      words >> type;
      if (type == "list")
      {
        std::string countType;
        words >> countType >> type;
        property.count = typeNamed(countType);
        if (property.count.bytes == 0 || property.count.isFloat)
        {
          throwFileError(
            path, "unknown or non-integer PLY list count type '" + countType.substr(0, 40) + "'");
        }
      }
      property.type = typeNamed(type);
      words >> property.name;
      if (property.type.bytes == 0)
      {
        throwFileError(path, "unknown PLY property type '" + type.substr(0, 40) + "'");
      }
      elements.back().properties.push_back(property);
    }
    else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty())
    {
      throwFileError(
        path, "a PLY header line starts with '" + keyword.substr(0, 40) + "', no PLY keyword");
    }
  }
  throwFileError(path, "not a PLY file (no end_header)");
}

} // namespace

PlyMesh readPlyMesh(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throwFileError(path, "cannot open the file");
  }
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t at = 0;
  PlyFormat format = PlyFormat::Ascii;
  const std::vector<PlyElement> elements = readHeader(path, data, at, format);
  const auto vertexElement = std::find_if(
    elements.begin(), elements.end(), [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertexElement == elements.end())
  {
    throwFileError(path, "the PLY file has no vertex element");
  }
  const std::uint64_t vertices = vertexElement->count;
  PlyMesh mesh;
  PlyValues values(path, data, at, format);
  for (const PlyElement& element : elements)
  {
    const bool isVertex = element.name == "vertex";
    const bool isFace = element.name == "face";
    std::array<int, 3> xyz{ -1, -1, -1 };
    int indices = -1;
    for (std::size_t k = 0; k < element.properties.size(); ++k)
    {
      const PlyProperty& p = element.properties[k];
      for (int axis = 0; axis < 3; ++axis)
      {
        if (isVertex && p.count.bytes == 0 && p.name == std::string(1, char('x' + axis)))
        {
          xyz[static_cast<std::size_t>(axis)] = static_cast<int>(k);
        }
      }
      if (isFace && p.count.bytes > 0 && !p.type.isFloat &&
        (p.name == "vertex_indices" || p.name == "vertex_index"))
      {
        indices = static_cast<int>(k);
      }
    }
    if (isVertex && std::count(xyz.begin(), xyz.end(), -1) > 0)
    {
      throwFileError(path, "the PLY vertex element lacks one of the properties x, y and z");
    }
    if (isFace && indices < 0)
    {
      throwFileError(path, "the PLY face element has no integer list 'vertex_indices'");
    }
    for (std::uint64_t i = 0; i < element.count; ++i)
    {
      values.start(element, i);
      std::array<double, 3> point{};
      for (std::size_t k = 0; k < element.properties.size(); ++k)
      {
        const PlyProperty& p = element.properties[k];
        if (p.count.bytes == 0)
        {
          const double v = values.next(p.type);
          for (int axis = 0; axis < 3; ++axis)
          {
            if (static_cast<int>(k) == xyz[static_cast<std::size_t>(axis)])
            {
              point[static_cast<std::size_t>(axis)] = v;
            }
          }
          continue;
        }
        const double items = values.next(p.count);
        if (!(items >= 0.0 && items <= 1e6) ||
          items != static_cast<double>(static_cast<long>(items)))
        {
          throwFileError(path, values.where() + " has a list of " + numberText(items) + " items");
        }
        std::vector<std::int64_t> face;
        for (long n = 0; n < static_cast<long>(items); ++n)
        {
          const double v = values.next(p.type);
          if (static_cast<int>(k) != indices)
          {
            continue;
          }
          if (!(v >= 0.0 && v < static_cast<double>(vertices)) ||
            v != static_cast<double>(static_cast<std::int64_t>(v)))
          {
            throwFileError(path,
              values.where() + " names vertex " + numberText(v) + "; the file has " +
                std::to_string(vertices));
          }
          face.push_back(static_cast<std::int64_t>(v));
        }
        if (static_cast<int>(k) == indices)
        {
          mesh.faces.push_back(std::move(face));
        }
      }
      if (isVertex)
      {
        mesh.points.push_back(point);
      }
    }
  }
  return mesh;
}

} // namespace vimlop::detail
