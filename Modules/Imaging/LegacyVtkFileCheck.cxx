#include <vimlop/Imaging/LegacyVtkFileCheck.h>

#include <vimlop/Imaging/MeshFileChecks.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>

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

/// Legacy VTK's data after the header, walked as its reader will read it:
/// words in ASCII files, big-endian values right after a keyword's line in
/// binary ones.
class LegacyVtkWalk
{
public:
  LegacyVtkWalk(const std::string& path, const std::string& data, std::size_t at, bool binary)
    : Path(path)
    , Data(data)
    , At(at)
    , Binary(binary)
  {
  }

  /// The next whitespace-separated word; "" at the end.
  std::string word()
  {
    while (this->At < this->Data.size() &&
      std::isspace(static_cast<unsigned char>(this->Data[this->At])))
    {
      ++this->At;
    }
    const std::size_t start = this->At;
    while (this->At < this->Data.size() &&
      !std::isspace(static_cast<unsigned char>(this->Data[this->At])))
    {
      ++this->At;
    }
    return this->Data.substr(start, this->At - start);
  }

  std::uint64_t count(const std::string& where)
  {
    const std::string w = this->word();
    if (w.empty() || w.size() > 19 || w.find_first_not_of("0123456789") != std::string::npos)
    {
      throwFileError(this->Path, "the " + where + " line has no count");
    }
    return std::stoull(w);
  }

  /// Where binary values of a keyword start: after the end of its line.
  void startValues()
  {
    if (this->Binary)
    {
      const std::size_t newline = this->Data.find('\n', this->At);
      this->At = newline == std::string::npos ? this->Data.size() : newline + 1;
    }
  }

  /// One integer value of `bytes` bytes (binary) or one word (ASCII).
  std::int64_t integer(int bytes, const std::string& where)
  {
    if (!this->Binary)
    {
      const std::string w = this->word();
      char* end = nullptr;
      const long long v = w.empty() ? 0 : std::strtoll(w.c_str(), &end, 10);
      if (w.empty() || *end != '\0')
      {
        throwFileError(this->Path, "the file ends or holds no integer inside the " + where);
      }
      return v;
    }
    this->need(static_cast<std::uint64_t>(bytes), where);
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i)
    {
      v = v << 8 | static_cast<unsigned char>(this->Data[this->At++]);
    }
    // Signed, as VTK's id types are.
    return bytes < 8 && (v >> (8 * bytes - 1)) != 0
      ? static_cast<std::int64_t>(v) - (std::int64_t(1) << (8 * bytes))
      : static_cast<std::int64_t>(v);
  }

  /// Skips `values` values of `bytes` bytes each.
  void skip(std::uint64_t values, int bytes, const std::string& where)
  {
    if (this->Binary)
    {
      if (values > (this->Data.size() - this->At) / static_cast<std::uint64_t>(bytes))
      {
        throwFileError(this->Path, "the file ends inside the " + where + " (truncated)");
      }
      this->At += static_cast<std::size_t>(values * static_cast<std::uint64_t>(bytes));
      return;
    }
    for (std::uint64_t i = 0; i < values; ++i)
    {
      const std::string w = this->word();
      if (w.empty())
      {
        throwFileError(this->Path, "the file ends inside the " + where + " (truncated)");
      }
      char* end = nullptr;
      std::strtod(w.c_str(), &end);
      if (*end != '\0')
      {
        // Counting it as a value would let the walk skip the next keyword.
        throwFileError(
          this->Path, "the " + where + " hold '" + w.substr(0, 20) + "', which is no number");
      }
    }
  }

private:
  void need(std::uint64_t bytes, const std::string& where) const
  {
    if (bytes > this->Data.size() - this->At)
    {
      throwFileError(this->Path, "the file ends inside the " + where + " (truncated)");
    }
  }

  const std::string& Path;
  const std::string& Data;
  std::size_t At;
  bool Binary;
};

/// The keyword a legacy VTK reader sees in `word`: it compares the start of
/// the word, lower-cased, so "POLYGONS!" and "polygons" are POLYGONS too.
std::string legacyKeyword(const std::string& word)
{
  const std::string lower = lowerCase(word);
  for (const char* keyword : { "dataset", "points", "vertices", "lines", "polygons",
         "triangle_strips", "point_data", "cell_data", "field", "metadata" })
  {
    if (lower.rfind(keyword, 0) == 0)
    {
      std::string upper = keyword;
      std::transform(upper.begin(), upper.end(), upper.begin(),
        [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
      return upper;
    }
  }
  return "";
}

/// Bytes of a legacy VTK data type; 0 when unknown.
int legacyTypeBytes(const std::string& type)
{
  if (type == "bit")
  {
    return 0; // packed bits: no VIMLOP mesh has them
  }
  if (type == "char" || type == "unsigned_char")
  {
    return 1;
  }
  if (type == "short" || type == "unsigned_short")
  {
    return 2;
  }
  if (type == "int" || type == "unsigned_int" || type == "float" || type == "vtktypeint32")
  {
    return 4;
  }
  if (type == "long" || type == "unsigned_long" || type == "double" || type == "vtkIdType" ||
    type == "vtktypeint64" || type == "vtktypeuint64")
  {
    return 8;
  }
  return 0;
}

} // namespace

namespace
{

/// The points and cell lists of a legacy VTK file, up to its first data
/// attributes (their counts are bounded above).
void walkLegacyVtkCells(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Four header lines: version, title, ASCII or BINARY, DATASET.
  std::size_t at = 0;
  std::vector<std::string> header;
  while (header.size() < 3 && at < data.size())
  {
    const std::size_t newline = std::min(data.find('\n', at), data.size());
    header.push_back(data.substr(at, newline - at));
    at = std::min(newline + 1, data.size());
  }
  if (header.size() < 3)
  {
    return; // VTK's reader refuses it
  }
  // Read as VTK reads it: "# vtk DataFile Version %d.%d"; anything else is an old file.
  int major = 0;
  int minor = 0;
  const bool offsets =
    std::sscanf(header[0].c_str(), "# vtk DataFile Version %d.%d", &major, &minor) == 2 &&
    major >= 5;
  // The file type line as VTK's writer writes it: its reader went on past a
  // mangled one and read from a stream it had closed.
  std::string type = header[2];
  type.erase(type.find_last_not_of(" \t\r") + 1);
  if (type != "ASCII" && type != "BINARY")
  {
    throwFileError(path, "line 3 is '" + type.substr(0, 40) + "', not ASCII or BINARY");
  }
  LegacyVtkWalk walk(path, data, at, type == "BINARY");
  std::uint64_t points = 0;
  for (std::string word = walk.word(); !word.empty(); word = walk.word())
  {
    const std::string keyword = legacyKeyword(word);
    if (keyword == "DATASET")
    {
      walk.word();
    }
    else if (keyword == "POINTS")
    {
      points = walk.count("POINTS");
      const std::string type = walk.word();
      const int bytes = legacyTypeBytes(type);
      if (bytes == 0)
      {
        throwFileError(path, "unknown type '" + type.substr(0, 40) + "' of the POINTS");
      }
      walk.startValues();
      walk.skip(3 * points, bytes, "POINTS");
    }
    else if (keyword == "VERTICES" || keyword == "LINES" || keyword == "POLYGONS" ||
      keyword == "TRIANGLE_STRIPS")
    {
      const std::uint64_t first = walk.count(keyword);
      const std::uint64_t second = walk.count(keyword);
      const auto checkId = [&](std::int64_t id, std::uint64_t cell)
      {
        if (id < 0 || static_cast<std::uint64_t>(id) >= points)
        {
          throwFileError(path,
            "cell " + std::to_string(cell) + " of the " + keyword + " names point " +
              std::to_string(id) + "; the file has " + std::to_string(points));
        }
      };
      if (!offsets)
      {
        // Each cell: its size, then its ids, `second` numbers in all.
        walk.startValues();
        std::uint64_t left = second;
        for (std::uint64_t cell = 0; cell < first; ++cell)
        {
          const std::int64_t size = left > 0 ? walk.integer(4, keyword) : -1;
          if (size < 0 || static_cast<std::uint64_t>(size) >= left)
          {
            throwFileError(path,
              "cell " + std::to_string(cell) + " of the " + keyword +
                " does not fit in the list's " + std::to_string(second) + " numbers");
          }
          left -= static_cast<std::uint64_t>(size) + 1;
          for (std::int64_t k = 0; k < size; ++k)
          {
            checkId(walk.integer(4, keyword), cell);
          }
        }
        continue;
      }
      // Version 5: OFFSETS (cells + 1 values from 0 to the ids), CONNECTIVITY (the ids).
      std::vector<std::int64_t> offsetValues;
      for (const char* part : { "OFFSETS", "CONNECTIVITY" })
      {
        if (walk.word() != part)
        {
          throwFileError(path, "the " + keyword + " lack their " + part);
        }
        const int bytes = legacyTypeBytes(walk.word());
        if (bytes != 4 && bytes != 8)
        {
          throwFileError(path, "the " + keyword + " " + part + " are not 32- or 64-bit integers");
        }
        walk.startValues();
        const std::uint64_t n = part[0] == 'O' ? first : second;
        for (std::uint64_t i = 0; i < n; ++i)
        {
          const std::int64_t v = walk.integer(bytes, keyword + " " + part);
          if (part[0] == 'O')
          {
            if (v < (offsetValues.empty() ? 0 : offsetValues.back()) ||
              static_cast<std::uint64_t>(v) > second || (i == 0 && v != 0))
            {
              throwFileError(path,
                "the " + keyword + " OFFSETS do not rise from 0 to the " + std::to_string(second) +
                  " ids of the CONNECTIVITY");
            }
            offsetValues.push_back(v);
          }
          else
          {
            const auto cell = std::upper_bound(offsetValues.begin(), offsetValues.end(),
                                static_cast<std::int64_t>(i)) -
              offsetValues.begin() - 1;
            checkId(v, static_cast<std::uint64_t>(std::max<std::ptrdiff_t>(cell, 0)));
          }
        }
        if (part[0] == 'O' && first > 0 &&
          static_cast<std::uint64_t>(offsetValues.back()) != second)
        {
          throwFileError(path,
            "the " + keyword + " OFFSETS do not rise from 0 to the " + std::to_string(second) +
              " ids of the CONNECTIVITY");
        }
      }
    }
    else if (keyword == "FIELD")
    {
      // The data set's field data: VTK's reader dereferenced the null it
      // got back from a field it could not read.
      walk.word(); // its name
      const std::uint64_t arrays = walk.count("FIELD");
      checkPromise(path, arrays, "field data arrays");
      for (std::uint64_t a = 0; a < arrays; ++a)
      {
        const std::string name = walk.word();
        if (legacyKeyword(name) == "METADATA")
        {
          return; // an array's information keys: VTK reads them itself
        }
        if (name == "NULL_ARRAY")
        {
          continue;
        }
        const std::uint64_t components = walk.count("FIELD array");
        const std::uint64_t tuples = walk.count("FIELD array");
        const std::string type = walk.word();
        const int bytes = legacyTypeBytes(type);
        if (bytes == 0)
        {
          throwFileError(path,
            "the FIELD array '" + name.substr(0, 40) + "' has the type '" + type.substr(0, 40) +
              "'; VIMLOP reads numeric field data only");
        }
        if (components == 0 || (tuples > 0 && components > maxMeshElements / tuples))
        {
          throwFileError(path,
            "the FIELD array '" + name.substr(0, 40) + "' promises " + std::to_string(components) +
              " components of " + std::to_string(tuples) + " tuples; at most " +
              std::to_string(maxMeshElements) + " values are read");
        }
        walk.startValues();
        walk.skip(components * tuples, bytes, "FIELD array '" + name.substr(0, 40) + "'");
      }
    }
    else if (keyword == "POINT_DATA" || keyword == "CELL_DATA" || keyword == "METADATA")
    {
      return; // data attributes: their counts are bounded above
    }
    else
    {
      throwFileError(
        path, "the file holds '" + word.substr(0, 40) + "' where a legacy VTK keyword should be");
    }
  }
}

} // namespace

/// Legacy VTK: the counts after POINTS, POLYGONS and the like, wherever they
/// are in the file (ASCII or binary data between them).
void checkLegacyVtk(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::string word;
    std::uint64_t count = 0;
    if (!(words >> word))
    {
      continue;
    }
    const std::string keyword = legacyKeyword(word);
    if (keyword == "POINTS" && (words >> count))
    {
      checkPromise(path, count, "points");
    }
    else if ((keyword == "VERTICES" || keyword == "LINES" || keyword == "POLYGONS" ||
               keyword == "TRIANGLE_STRIPS") &&
      (words >> count))
    {
      checkPromise(path, count, "cells");
      std::uint64_t size = 0;
      if (words >> size)
      {
        // Every cell lists at least one point id, besides its size or offset.
        checkPromise(path, size / 4, "cells (" + std::to_string(size) + " cell ids)");
      }
    }
    else if ((keyword == "POINT_DATA" || keyword == "CELL_DATA") && (words >> count))
    {
      checkPromise(path, count, "data values");
    }
  }
  walkLegacyVtkCells(path);
}

} // namespace vimlop::detail
