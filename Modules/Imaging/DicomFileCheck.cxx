#include <vimlop/Imaging/DicomFileCheck.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Imaging/DicomAttributeRules.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

namespace vimlop::detail
{

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
          throwFileError(this->Path,
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
        // The walk reads little-endian elements: a big-endian or deflated data
        // set would be judged on bytes that GDCM reads otherwise.
        if (uid == "1.2.840.10008.1.2.2" || uid == "1.2.840.10008.1.2.1.99")
        {
          throwFileError(this->Path,
            "the DICOM file's transfer syntax " + uid + " (" +
              (uid == "1.2.840.10008.1.2.2" ? "explicit VR big endian, retired"
                                            : "deflated explicit VR little endian") +
              ") is not read; convert the series to explicit VR little endian");
        }
      }
      at = value + static_cast<std::size_t>(length);
    }
    if (at == 132)
    {
      // GDCM's reading of a file without one asserted on what it found instead.
      throwFileError(
        this->Path, "the DICOM file has no file meta information group (0002) after 'DICM'");
    }
    if (groupEnd != 0 && at != groupEnd)
    {
      this->corrupt(at, "does not end the file meta group where its group length says");
    }
    return at;
  }

  /// The data set from `at` to the end of the file.
  void dataSet(std::size_t at, bool implicit)
  {
    const std::size_t stop = this->elements(at, this->Data.size(), implicit, 0);
    if (stop != this->Data.size())
    {
      this->corrupt(stop, "is an item or delimiter outside any sequence");
    }
  }

  /// Elements from `at` to `end`, or to the first item tag or delimiter
  /// (FFFE,xxxx), which is the caller's: returns where they stopped.
  std::size_t elements(std::size_t at, std::size_t end, bool implicit, int depth)
  {
    if (depth > 16)
    {
      this->corrupt(at, "lies in sequences nested more than 16 deep");
    }
    DicomPixelFormat format; // of this data set (an item has its own, an icon's)
    // Where the data set ends, its rescale is judged against its pixel format.
    const auto done = [&](std::size_t stop)
    {
      const std::string problem = rescaleProblem(format);
      if (!problem.empty())
      {
        throwFileError(this->Path, "the DICOM file is corrupt: " + problem);
      }
      return stop;
    };
    while (at + 8 <= end)
    {
      const std::uint32_t group = this->u16(at);
      const std::uint32_t element = this->u16(at + 2);
      if (group == 0xFFFE)
      {
        return done(at); // an item or delimiter: the caller's
      }
      const bool isImplicit = implicit;
      const std::size_t value =
        isImplicit ? this->implicitElement(at, end) : this->explicitElement(at, end);
      const char* const standardVr = typedAttributeVr(group, element);
      if (standardVr != nullptr && !isImplicit && this->Vr != standardVr && this->Vr != "UN")
      {
        this->corrupt(at,
          "has the value representation '" + this->Vr + "' where the standard has " + standardVr);
      }
      const bool text = this->Length != Undefined && this->Length > 0;
      if (group == 0x0008 && element == 0x0010 && depth == 0 && text)
      {
        this->judge(at, recognitionCodeProblem(this->value(value)));
      }
      if (group == 0x0028 && element == 0x1052 && text)
      {
        this->judge(
          at, decimalProblem(this->value(value), "Rescale Intercept", format.rescaleIntercept));
      }
      if (group == 0x0028 && element == 0x1053 && text)
      {
        this->judge(at, decimalProblem(this->value(value), "Rescale Slope", format.rescaleSlope));
      }
      if (this->Length == Undefined)
      {
        // Items up to their delimiter: a sequence's data sets (in implicit
        // VR inside a UN, as Part 5 has it) or encapsulated pixel data's
        // fragments.
        const bool fragments = group == 0x7FE0 && element == 0x0010;
        at = this->items(value, end, implicit || this->Vr == "UN", depth + 1, fragments);
        continue;
      }
      // GDCM asserts when an image attribute it reads as one number has
      // another length: Samples per Pixel, Rows, Columns, Bits Allocated,
      // Bits Stored, High Bit, Pixel Representation, Planar Configuration.
      static const std::uint32_t oneUS[] = { 0x0002, 0x0006, 0x0010, 0x0011, 0x0100, 0x0101, 0x0102,
        0x0103 };
      const bool imageNumber = group == 0x0028 &&
        std::find(std::begin(oneUS), std::end(oneUS), element) != std::end(oneUS);
      if (imageNumber && this->Length != 2)
      {
        this->corrupt(
          at, "holds " + std::to_string(this->Length) + " bytes where one 16-bit number belongs");
      }
      if (imageNumber)
      {
        this->judge(at, pixelFormatProblem(element, this->u16(value), format));
      }
      if (!isImplicit && this->Length % this->ValueSize != 0)
      {
        this->corrupt(
          at, "holds " + std::to_string(this->Length) + " bytes, no whole number of its values");
      }
      // A sequence of defined length; in implicit VR, a value that starts
      // as an item (GDCM reads one so when its dictionary does not know the tag).
      const std::size_t valueEnd = value + static_cast<std::size_t>(this->Length);
      const bool startsAnItem =
        this->Length >= 8 && this->u16(value) == 0xFFFE && this->u16(value + 2) == 0xE000;
      if (this->IsSequence || (isImplicit && startsAnItem))
      {
        this->items(value, valueEnd, implicit, depth + 1, false);
      }
      at = valueEnd;
    }
    this->leftover(at, end);
    return done(at);
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

  /// The bytes of the current element's value at `value`.
  std::string value(std::size_t value) const
  {
    return this->Data.substr(value, static_cast<std::size_t>(this->Length));
  }

  /// Refuses the element at `at` when a rule found a problem with it.
  void judge(std::size_t at, const std::string& problem) const
  {
    if (!problem.empty())
    {
      this->corrupt(at, problem);
    }
  }

  [[noreturn]] void corrupt(std::size_t at, const std::string& problem) const
  {
    char tag[16] = "";
    if (at + 4 <= this->Data.size())
    {
      std::snprintf(tag, sizeof(tag), " (%04X,%04X)", this->u16(at), this->u16(at + 2));
    }
    throwFileError(this->Path,
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
      throwFileError(this->Path,
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
    this->IsSequence = false; // not known without a dictionary (see elements())
    this->Vr.clear();
    this->ValueSize = 1;
    this->Length = this->u32(at + 4);
    this->bound(at, at + 8, end);
    return at + 8;
  }

  /// Items (FFFE,E000) up to `end` or a sequence delimiter (FFFE,E0DD):
  /// data sets, walked in turn, or pixel data `fragments`, bounded.
  std::size_t items(std::size_t at, std::size_t end, bool implicit, int depth, bool fragments)
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
        if (fragments)
        {
          this->corrupt(at, "is a pixel data fragment without a length");
        }
        at = this->elements(value, end, implicit, depth);
        if (at + 8 > end || this->u16(at) != 0xFFFE || this->u16(at + 2) != 0xE00D)
        {
          this->corrupt(at < end ? at : value, "ends an item without its delimiter");
        }
        at += 8;
        continue;
      }
      this->bound(at, value, end);
      const std::size_t itemEnd = value + static_cast<std::size_t>(this->Length);
      const std::size_t stop =
        fragments ? itemEnd : this->elements(value, itemEnd, implicit, depth);
      if (stop != itemEnd)
      {
        this->corrupt(stop, "stands inside an item where a data element should");
      }
      at = itemEnd;
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
      throwFileError(this->Path,
        "the file is truncated: it ends inside an element at byte " + std::to_string(at));
    }
    throwFileError(this->Path,
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
    throwFileError(path, "not a DICOM file (no 'DICM' at byte 128)");
  }
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  DicomWalk walk(path, data);
  bool implicit = false;
  const std::size_t dataSet = walk.metaGroup(implicit);
  if (dataSet + 8 > data.size())
  {
    // GDCM asserted reading the data set's first tag.
    throwFileError(
      path, "the file is truncated: it ends after its file meta group, without a data set");
  }
  walk.dataSet(dataSet, implicit);
}

} // namespace vimlop::detail
