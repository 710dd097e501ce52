#include <vimlop/Imaging/InVesaliusProjectReader.h>

#include <vimlop/Core/FileError.h>

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>

namespace vimlop
{

namespace
{

/// No single archive member we keep may exceed this (a guard against bombs).
constexpr std::uint64_t MaxMemberBytes = std::uint64_t(4) << 30;

std::string baseName(const std::string& name)
{
  const auto slash = name.find_last_of('/');
  return slash == std::string::npos ? name : name.substr(slash + 1);
}

/// Reads exactly `n` bytes; returns false on a clean or truncated end of stream.
bool readExactly(gzFile file, char* buffer, std::size_t n)
{
  std::size_t done = 0;
  while (done < n)
  {
    const int chunk = static_cast<int>(std::min<std::size_t>(n - done, 1 << 30));
    const int got = gzread(file, buffer + done, static_cast<unsigned>(chunk));
    if (got <= 0)
    {
      return false;
    }
    done += static_cast<std::size_t>(got);
  }
  return true;
}

std::uint64_t parseOctal(const char* field, std::size_t width, bool& ok)
{
  std::uint64_t value = 0;
  std::size_t i = 0;
  while (i < width && (field[i] == ' ' || field[i] == '\0'))
  {
    ++i;
  }
  bool any = false;
  for (; i < width && field[i] >= '0' && field[i] <= '7'; ++i)
  {
    if (value > (std::uint64_t(1) << 60))
    {
      ok = false;
      return 0;
    }
    value = value * 8 + static_cast<std::uint64_t>(field[i] - '0');
    any = true;
  }
  ok = any;
  return value;
}

/// The archive members VIMLOP needs: main.plist and the raw .dat arrays, by base name.
std::map<std::string, std::string> readMembers(const std::string& path)
{
  std::unique_ptr<std::remove_pointer_t<gzFile>, int (*)(gzFile)> file(
    gzopen(path.c_str(), "rb"), gzclose);
  if (!file)
  {
    throwFileError(path, "cannot open the file");
  }
  std::map<std::string, std::string> members;
  char header[512];
  bool sawEnd = false;
  while (readExactly(file.get(), header, sizeof(header)))
  {
    if (std::all_of(header, header + sizeof(header), [](char c) { return c == '\0'; }))
    {
      sawEnd = true;
      break;
    }
    bool ok = false;
    const std::uint64_t size = parseOctal(header + 124, 12, ok);
    if (!ok)
    {
      throwFileError(path, "not an InVesalius project (invalid tar header)");
    }
    std::string name(header, strnlen(header, 100));
    const std::string prefix(header + 345, strnlen(header + 345, 155));
    if (std::memcmp(header + 257, "ustar", 5) == 0 && !prefix.empty())
    {
      name = prefix + "/" + name;
    }
    const char type = header[156];
    const std::string base = baseName(name);
    const bool wanted = (type == '0' || type == '\0') &&
      (base == "main.plist" || (base.size() > 4 && base.compare(base.size() - 4, 4, ".dat") == 0));
    const std::uint64_t padded = (size + 511) / 512 * 512;
    if (wanted)
    {
      if (size > MaxMemberBytes)
      {
        throwFileError(path, "archive member '" + name + "' is too large");
      }
      // Grow with the data actually read, never with what the header claims.
      std::string content;
      char chunk[1 << 16];
      for (std::uint64_t left = size; left > 0;)
      {
        const std::size_t n =
          static_cast<std::size_t>(std::min<std::uint64_t>(left, sizeof(chunk)));
        if (!readExactly(file.get(), chunk, n))
        {
          throwFileError(path, "archive is truncated inside '" + name + "'");
        }
        content.append(chunk, n);
        left -= n;
      }
      members[base] = std::move(content);
      char skip[512];
      if (padded > size && !readExactly(file.get(), skip, static_cast<std::size_t>(padded - size)))
      {
        throwFileError(path, "archive is truncated inside '" + name + "'");
      }
    }
    else
    {
      // Skip members we do not need without buffering them.
      if (gzseek(file.get(), static_cast<z_off_t>(padded), SEEK_CUR) < 0)
      {
        throwFileError(path, "archive is truncated inside '" + name + "'");
      }
    }
  }
  int zerr = Z_OK;
  const char* zmessage = gzerror(file.get(), &zerr);
  if (zerr != Z_OK && zerr != Z_STREAM_END)
  {
    throwFileError(path, std::string("not a readable gzip archive (") + zmessage + ")");
  }
  if (!sawEnd && members.empty())
  {
    throwFileError(path, "not an InVesalius project (no tar archive inside)");
  }
  return members;
}

/// The value element that follows <key>name</key> in a plist <dict>.
vtkXMLDataElement* dictValue(vtkXMLDataElement* dict, const char* key)
{
  if (!dict)
  {
    return nullptr;
  }
  const int n = dict->GetNumberOfNestedElements();
  for (int i = 0; i + 1 < n; ++i)
  {
    vtkXMLDataElement* e = dict->GetNestedElement(i);
    if (std::strcmp(e->GetName(), "key") == 0 && e->GetCharacterData() &&
      std::strcmp(e->GetCharacterData(), key) == 0)
    {
      return dict->GetNestedElement(i + 1);
    }
  }
  return nullptr;
}

std::string text(vtkXMLDataElement* e)
{
  return e && e->GetCharacterData() ? std::string(e->GetCharacterData()) : std::string();
}

std::vector<double> numberArray(vtkXMLDataElement* e)
{
  std::vector<double> values;
  if (!e || std::strcmp(e->GetName(), "array") != 0)
  {
    return values;
  }
  for (int i = 0; i < e->GetNumberOfNestedElements(); ++i)
  {
    const std::string s = text(e->GetNestedElement(i));
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end == s.c_str())
    {
      return {};
    }
    values.push_back(v);
  }
  return values;
}

} // namespace

CTVolume readInVesaliusProject(const std::string& path)
{
  const std::map<std::string, std::string> members = readMembers(path);
  const auto plistIt = members.find("main.plist");
  if (plistIt == members.end())
  {
    throwFileError(path, "not an InVesalius project (no main.plist in the archive)");
  }
  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromString(plistIt->second.c_str()));
  vtkXMLDataElement* dict =
    root && root->GetNumberOfNestedElements() > 0 ? root->GetNestedElement(0) : nullptr;
  if (!dict || std::strcmp(dict->GetName(), "dict") != 0)
  {
    throwFileError(path, "main.plist is not a property list dictionary");
  }
  vtkXMLDataElement* matrix = dictValue(dict, "matrix");
  const std::string dtype = text(dictValue(matrix, "dtype"));
  const std::string matrixFile = text(dictValue(matrix, "filename"));
  const std::vector<double> shape = numberArray(dictValue(matrix, "shape"));
  const std::vector<double> spacing = numberArray(dictValue(dict, "spacing"));
  if (!matrix || matrixFile.empty() || shape.size() != 3)
  {
    throwFileError(path, "main.plist does not describe the volume matrix (filename and 3-D shape)");
  }
  if (dtype != "int16")
  {
    throwFileError(path, "unsupported matrix type '" + dtype + "' (InVesalius volumes are int16)");
  }
  if (spacing.size() != 3 ||
    !std::all_of(
      spacing.begin(), spacing.end(), [](double s) { return std::isfinite(s) && s > 0.0; }))
  {
    throwFileError(path, "main.plist has no valid spacing (three positive numbers)");
  }
  CTVolume volume;
  volume.format = "InVesalius project";
  // The plist shape is (z, y, x); our dims are (x, y, z).
  for (int axis = 0; axis < 3; ++axis)
  {
    const double n = shape[2 - axis];
    if (!(n >= 1.0 && n <= 65536.0) || n != std::floor(n))
    {
      throwFileError(path, "main.plist has an invalid matrix shape");
    }
    volume.dims[axis] = static_cast<int>(n);
    volume.spacingMm[axis] = spacing[axis];
  }
  const auto dataIt = members.find(baseName(matrixFile));
  if (dataIt == members.end())
  {
    throwFileError(path, "the archive has no '" + matrixFile + "' named by main.plist");
  }
  const std::string& raw = dataIt->second;
  if (raw.size() != volume.numberOfVoxels() * sizeof(std::int16_t))
  {
    std::ostringstream msg;
    msg << "'" << matrixFile << "' holds " << raw.size() << " bytes but the shape "
        << volume.dims[2] << "x" << volume.dims[1] << "x" << volume.dims[0] << " needs "
        << volume.numberOfVoxels() * sizeof(std::int16_t);
    throwFileError(path, msg.str());
  }
  volume.intensities.resize(volume.numberOfVoxels());
  const auto* bytes = reinterpret_cast<const unsigned char*>(raw.data());
  for (std::size_t i = 0; i < volume.intensities.size(); ++i)
  {
    // Little-endian whatever the host, as numpy wrote it.
    const auto v = static_cast<std::int16_t>(bytes[2 * i] | (bytes[2 * i + 1] << 8));
    volume.intensities[i] = static_cast<float>(v);
  }
  volume.direction = { 1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0 };
  volume.originMm = { 0.0, (volume.dims[1] - 1) * volume.spacingMm[1], 0.0 };
  return volume;
}

} // namespace vimlop
