#include <vimlop/Imaging/DicomAttributeRules.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace vimlop::detail
{

namespace
{

/// At most 24 characters of a value, the unprintable ones as '?'.
std::string shown(const std::string& text)
{
  std::string s = text.substr(0, 24);
  for (char& c : s)
  {
    c = std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  }
  return s;
}

/// A DICOM string value without its padding.
std::string trimmed(std::string text)
{
  text.erase(0, text.find_first_not_of(std::string(" \0", 2)));
  text.erase(text.find_last_not_of(std::string(" \0", 2)) + 1);
  return text;
}

} // namespace

const char* typedAttributeVr(std::uint32_t group, std::uint32_t element)
{
  struct Typed
  {
    std::uint32_t group;
    std::uint32_t element;
    const char* vr;
  };
  static const Typed typed[] = { { 0x0008, 0x0010, "SH" }, { 0x0008, 0x0070, "LO" },
    { 0x0008, 0x0100, "SH" }, { 0x0008, 0x0104, "LO" }, { 0x0018, 0x0050, "DS" },
    { 0x0018, 0x0088, "DS" }, { 0x0018, 0x1063, "DS" }, { 0x0018, 0x602c, "FD" },
    { 0x0018, 0x602e, "FD" }, { 0x0020, 0x0030, "DS" }, { 0x0020, 0x0032, "DS" },
    { 0x0020, 0x0035, "DS" }, { 0x0020, 0x0037, "DS" }, { 0x0028, 0x0002, "US" },
    { 0x0028, 0x0005, "US" }, { 0x0028, 0x0006, "US" }, { 0x0028, 0x0008, "IS" },
    { 0x0028, 0x0009, "AT" }, { 0x0028, 0x0010, "US" }, { 0x0028, 0x0011, "US" },
    { 0x0028, 0x0012, "US" }, { 0x0028, 0x0030, "DS" }, { 0x0028, 0x0034, "IS" },
    { 0x0028, 0x0100, "US" }, { 0x0028, 0x0101, "US" }, { 0x0028, 0x0102, "US" },
    { 0x0028, 0x0103, "US" }, { 0x0028, 0x1052, "DS" }, { 0x0028, 0x1053, "DS" },
    { 0x0028, 0x1054, "LO" }, { 0x0028, 0x2110, "CS" }, { 0x0040, 0x9224, "FD" },
    { 0x0040, 0x9225, "FD" }, { 0x0048, 0x0006, "UL" }, { 0x0048, 0x0007, "UL" },
    { 0x3004, 0x000c, "DS" }, { 0x3004, 0x000e, "DS" }, { 0x5400, 0x1004, "US" },
    { 0x6000, 0x0010, "US" }, { 0x6000, 0x0011, "US" }, { 0x6000, 0x0015, "IS" },
    { 0x6000, 0x0050, "SS" }, { 0x6000, 0x0051, "US" }, { 0x6000, 0x0100, "US" },
    { 0x6000, 0x0102, "US" }, { 0x6000, 0x0200, "US" }, { 0x5000, 0x0005, "US" },
    { 0x5000, 0x0010, "US" }, { 0x5000, 0x0103, "US" }, { 0x5000, 0x0110, "US" },
    { 0x5000, 0x0112, "US" }, { 0x5000, 0x0114, "US" } };
  // The repeating groups: overlays (60xx) and curves (50xx), even groups.
  if ((group & 0xFF01) == 0x6000 || (group & 0xFF01) == 0x5000)
  {
    group &= 0xFF00;
  }
  for (const Typed& t : typed)
  {
    if (t.group == group && t.element == element)
    {
      return t.vr;
    }
  }
  return nullptr;
}

std::string pixelFormatProblem(std::uint32_t element, std::uint32_t v, DicomPixelFormat& format)
{
  const std::string value = std::to_string(v);
  switch (element)
  {
    case 0x0002:
      format.samplesPerPixel = v;
      return v == 1 || v == 3 || v == 4
        ? ""
        : "gives Samples per Pixel " + value + ", where DICOM allows 1, 3 or 4";
    case 0x0006:
      return v <= 1 ? "" : "gives Planar Configuration " + value + ", where DICOM allows 0 or 1";
    case 0x0100:
      format.bitsAllocated = v;
      return v == 8 || v == 16 || v == 32
        ? ""
        : "gives Bits Allocated " + value + "; VIMLOP reads 8, 16 or 32";
    case 0x0101:
      if (v == 0 || v > format.bitsAllocated)
      {
        return "gives Bits Stored " + value + ", not from 1 to the Bits Allocated" +
          (format.bitsAllocated == 0 ? std::string(" (not given before it)")
                                     : " of " + std::to_string(format.bitsAllocated));
      }
      format.bitsStored = v;
      return "";
    case 0x0102:
    {
      const std::uint32_t stored = format.bitsStored;
      return v < stored ? ""
                        : "gives High Bit " + value + ", not below the Bits Stored" +
          (stored == 0 ? std::string(" (not given before it)") : " of " + std::to_string(stored));
    }
    case 0x0103:
      format.pixelRepresentation = v;
      return v <= 1
        ? ""
        : "gives Pixel Representation " + value + ", where DICOM allows 0 (unsigned) or 1 (signed)";
    default:
      return "";
  }
}

std::string recognitionCodeProblem(std::string code)
{
  code = trimmed(code);
  return code == "ACR-NEMA 1.0" || code == "ACR-NEMA 2.0" ? ""
                                                          : "gives the retired Recognition Code '" +
      shown(code) + "'; GDCM reads only ACR-NEMA 1.0 or 2.0 there";
}

std::string decimalProblem(std::string text, const char* name, double& value)
{
  text = trimmed(text);
  char* end = nullptr;
  value = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
  {
    return "gives the " + std::string(name) + " '" + shown(text) + "', not a number";
  }
  return "";
}

std::string rescaleProblem(const DicomPixelFormat& format)
{
  const double slope = format.rescaleSlope;
  const double intercept = format.rescaleIntercept;
  const bool whole = slope == std::trunc(slope) && intercept == std::trunc(intercept) &&
    std::abs(slope) < 2147483648.0 && std::abs(intercept) < 2147483648.0;
  if ((slope == 1.0 && intercept == 0.0) || !whole || format.samplesPerPixel != 1 ||
    format.bitsAllocated == 0)
  {
    return ""; // no rescale, one to floating point, or no image
  }
  const std::uint32_t stored = format.bitsStored == 0 ? format.bitsAllocated : format.bitsStored;
  const bool isSigned = format.pixelRepresentation == 1;
  const double low = isSigned ? -std::ldexp(1.0, static_cast<int>(stored) - 1) : 0.0;
  const double high = isSigned ? std::ldexp(1.0, static_cast<int>(stored) - 1) - 1.0
                               : std::ldexp(1.0, static_cast<int>(stored)) - 1.0;
  const double min = slope * (slope >= 0.0 ? low : high) + intercept;
  const double max = slope * (slope >= 0.0 ? high : low) + intercept;
  // GDCM's order of scalar types: UINT8, INT8, UINT12, INT12, UINT16, INT16,
  // UINT32, INT32, ..., FLOAT64 (12) for what needs more than 32 bits.
  const auto rank = [](std::uint32_t bits, bool s) {
    return (bits == 8 ? 0 : bits == 16 ? 4 : 6) + (s ? 1 : 0);
  };
  int output = 12;
  if (min >= 0.0)
  {
    output = max <= 255.0   ? rank(8, false)
      : max <= 65535.0      ? rank(16, false)
      : max <= 4294967295.0 ? rank(32, false)
                            : 12;
  }
  else
  {
    output = min >= -128.0 && max <= 127.0          ? rank(8, true)
      : min >= -32768.0 && max <= 32767.0           ? rank(16, true)
      : min >= -2147483648.0 && max <= 2147483647.0 ? rank(32, true)
                                                    : 12;
  }
  if (rank(format.bitsAllocated, isSigned) <= output)
  {
    return "";
  }
  char text[256];
  std::snprintf(text, sizeof(text),
    "the Rescale Slope %g and Intercept %g of its %u %s bits stored (of %u) map the pixels onto "
    "a narrower type, on which ITK's DICOM reader aborts",
    slope, intercept, stored, isSigned ? "signed" : "unsigned", format.bitsAllocated);
  return text;
}

} // namespace vimlop::detail
