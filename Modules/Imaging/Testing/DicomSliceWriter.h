#ifndef vimlop_DicomSliceWriter_h
#define vimlop_DicomSliceWriter_h

// Writes one CT slice as a DICOM Part 10 file (explicit VR little endian)
// byte by byte, so that a test can give it any geometry: a tilted stack, a
// gap, a NaN spacing, a truncated file. ITK's writer would replace the
// geometry elements with its own image's.

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace vimlop::fixtures
{

/// @brief One slice to write; the strings are the DICOM values as text.
struct DicomSliceSpec
{
  std::string seriesUID = "1.2.826.0.1.3680043.2.1125.2001";
  std::string position = "0\\0\\0";
  std::string orientation = "1\\0\\0\\0\\1\\0";
  std::string pixelSpacing = "0.5\\0.5";
  int rows = 8;
  int columns = 8;
  int instance = 1;
  /// Every pixel's stored value (HU, rescale 1/0).
  std::int16_t value = -1000;
  /// Bytes cut off the end of the file (a truncated copy).
  std::size_t truncateBytes = 0;
};

namespace detail
{

inline void put16(std::string& out, std::uint16_t v)
{
  out.push_back(static_cast<char>(v & 0xff));
  out.push_back(static_cast<char>(v >> 8));
}

inline void put32(std::string& out, std::uint32_t v)
{
  put16(out, static_cast<std::uint16_t>(v & 0xffff));
  put16(out, static_cast<std::uint16_t>(v >> 16));
}

/// One explicit-VR element; text values are padded to even length.
inline void element(
  std::string& out, std::uint16_t group, std::uint16_t tag, const char* vr, std::string value)
{
  if (value.size() % 2)
  {
    value.push_back(std::string(vr) == "UI" ? '\0' : ' ');
  }
  put16(out, group);
  put16(out, tag);
  out.append(vr, 2);
  const std::string v = vr;
  if (v == "OB" || v == "OW" || v == "SQ" || v == "UN" || v == "UT")
  {
    put16(out, 0);
    put32(out, static_cast<std::uint32_t>(value.size()));
  }
  else
  {
    put16(out, static_cast<std::uint16_t>(value.size()));
  }
  out += value;
}

inline std::string us(std::uint16_t v)
{
  std::string s;
  put16(s, v);
  return s;
}

} // namespace detail

/// @brief Writes `spec` to `path` as a CT Image Storage file.
inline void writeDicomSlice(const std::string& path, const DicomSliceSpec& spec)
{
  using detail::element;
  using detail::us;
  const std::string sopClass = "1.2.840.10008.5.1.4.1.1.2";
  const std::string instanceUID = spec.seriesUID + "." + std::to_string(spec.instance);
  std::string meta;
  element(meta, 0x0002, 0x0001, "OB", std::string("\0\1", 2));
  element(meta, 0x0002, 0x0002, "UI", sopClass);
  element(meta, 0x0002, 0x0003, "UI", instanceUID);
  element(meta, 0x0002, 0x0010, "UI", "1.2.840.10008.1.2.1");
  std::string file(128, '\0');
  file += "DICM";
  std::string length;
  detail::put32(length, static_cast<std::uint32_t>(meta.size()));
  element(file, 0x0002, 0x0000, "UL", length);
  file += meta;
  element(file, 0x0008, 0x0016, "UI", sopClass);
  element(file, 0x0008, 0x0018, "UI", instanceUID);
  element(file, 0x0008, 0x0060, "CS", "CT");
  element(file, 0x0010, 0x0020, "LO", "PHANTOM");
  element(file, 0x0020, 0x000d, "UI", spec.seriesUID + ".0");
  element(file, 0x0020, 0x000e, "UI", spec.seriesUID);
  element(file, 0x0020, 0x0013, "IS", std::to_string(spec.instance));
  element(file, 0x0020, 0x0032, "DS", spec.position);
  element(file, 0x0020, 0x0037, "DS", spec.orientation);
  element(file, 0x0028, 0x0002, "US", us(1));
  element(file, 0x0028, 0x0004, "CS", "MONOCHROME2");
  element(file, 0x0028, 0x0010, "US", us(static_cast<std::uint16_t>(spec.rows)));
  element(file, 0x0028, 0x0011, "US", us(static_cast<std::uint16_t>(spec.columns)));
  element(file, 0x0028, 0x0030, "DS", spec.pixelSpacing);
  element(file, 0x0028, 0x0100, "US", us(16));
  element(file, 0x0028, 0x0101, "US", us(16));
  element(file, 0x0028, 0x0102, "US", us(15));
  element(file, 0x0028, 0x0103, "US", us(1));
  element(file, 0x0028, 0x1052, "DS", "0");
  element(file, 0x0028, 0x1053, "DS", "1");
  std::string pixels;
  for (int i = 0; i < spec.rows * spec.columns; ++i)
  {
    detail::put16(pixels, static_cast<std::uint16_t>(spec.value));
  }
  element(file, 0x7fe0, 0x0010, "OW", pixels);
  file.resize(file.size() - std::min(spec.truncateBytes, file.size()));
  std::ofstream(path, std::ios::binary) << file;
}

/// @brief Writes a series of `slices.size()` slices as `slice<k>.dcm` into `folder`.
inline void writeDicomSeries(const std::string& folder, const std::vector<DicomSliceSpec>& slices)
{
  for (std::size_t k = 0; k < slices.size(); ++k)
  {
    writeDicomSlice(folder + "/slice" + std::to_string(k) + ".dcm", slices[k]);
  }
}

} // namespace vimlop::fixtures

#endif
