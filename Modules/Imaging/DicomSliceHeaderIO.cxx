// readDicomSliceHeader(): GDCM reads the elements ITK's series reader would
// use, as the header states them, so that checkDicomSeriesGeometry() judges
// what ITK would otherwise silently replace (an identity orientation for a
// zero one, 1 mm for a NaN spacing, -1024 HU for missing pixels).
#include <vimlop/Imaging/DicomSeriesGeometry.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Imaging/DicomFileCheck.h>

#include <gdcmDataSet.h>
#include <gdcmExplicitDataElement.h>
#include <gdcmFile.h>
#include <gdcmImplicitDataElement.h>
#include <gdcmReader.h>
#include <gdcmStringFilter.h>
#include <gdcmTag.h>
#include <gdcmTransferSyntax.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

namespace vimlop
{

namespace
{

/// A DICOM multi-valued decimal string ("1.5\-2\3e1") as `count` numbers;
/// NaN in every place when it does not hold exactly that many.
template <std::size_t count>
std::array<double, count> decimals(const std::string& text)
{
  std::array<double, count> values{};
  values.fill(std::numeric_limits<double>::quiet_NaN());
  std::array<double, count> parsed{};
  std::size_t n = 0;
  std::size_t start = 0;
  while (start <= text.size())
  {
    const std::size_t end = std::min(text.find('\\', start), text.size());
    const std::string item = text.substr(start, end - start);
    char* stop = nullptr;
    const double v = std::strtod(item.c_str(), &stop);
    if (n == count || stop == item.c_str() ||
      std::string(stop).find_first_not_of(' ') != std::string::npos)
    {
      return values;
    }
    parsed[n++] = v;
    start = end + 1;
  }
  return n == count ? parsed : values;
}

} // namespace

DicomSliceHeader readDicomSliceHeader(const std::string& file)
{
  detail::checkDicomPart10(file); // before GDCM parses it
  const gdcm::Tag pixelData(0x7fe0, 0x0010);
  gdcm::Reader reader;
  reader.SetFileName(file.c_str());
  if (!reader.Read())
  {
    throwFileError(file, "not a DICOM file GDCM can read");
  }
  const gdcm::File& dicom = reader.GetFile();
  const gdcm::DataSet& data = dicom.GetDataSet();
  gdcm::StringFilter strings;
  strings.SetFile(dicom);
  const auto present = [&](std::uint16_t group, std::uint16_t element)
  { return data.FindDataElement(gdcm::Tag(group, element)); };
  const auto text = [&](std::uint16_t group, std::uint16_t element)
  { return present(group, element) ? strings.ToString(gdcm::Tag(group, element)) : std::string(); };
  const auto integer = [&](std::uint16_t group, std::uint16_t element, long fallback)
  {
    const std::string value = text(group, element);
    char* stop = nullptr;
    const long v = std::strtol(value.c_str(), &stop, 10);
    return stop == value.c_str() ? fallback : v;
  };

  DicomSliceHeader header;
  header.file = file;
  const auto trimmed = [&](std::uint16_t group, std::uint16_t element)
  {
    std::string value = text(group, element);
    while (!value.empty() && (value.back() == ' ' || value.back() == '\0'))
    {
      value.pop_back();
    }
    return value;
  };
  header.seriesInstanceUID = trimmed(0x0020, 0x000e);
  header.studyInstanceUID = trimmed(0x0020, 0x000d);
  header.patientID = trimmed(0x0010, 0x0020);
  header.hasPosition = present(0x0020, 0x0032);
  header.positionMm = decimals<3>(text(0x0020, 0x0032));
  header.hasOrientation = present(0x0020, 0x0037);
  header.orientation = decimals<6>(text(0x0020, 0x0037));
  header.hasPixelSpacing = present(0x0028, 0x0030);
  header.pixelSpacingMm = decimals<2>(text(0x0028, 0x0030));
  header.rows = static_cast<int>(integer(0x0028, 0x0010, 0));
  header.columns = static_cast<int>(integer(0x0028, 0x0011, 0));

  const gdcm::TransferSyntax& syntax = dicom.GetHeader().GetDataSetTransferSyntax();
  if (!syntax.IsEncapsulated())
  {
    // GDCM fills pixel data cut short up to their declared length, so count
    // what the file holds after the pixel data element's start: the
    // encoded lengths of the file meta group and of the elements before it.
    const bool implicit = syntax.GetNegociatedType() == gdcm::TransferSyntax::Implicit;
    std::uint64_t start = dicom.GetHeader().GetFullLength(); // preamble included
    for (const gdcm::DataElement& element : data.GetDES())
    {
      if (!(element.GetTag() < pixelData))
      {
        break;
      }
      start += implicit ? static_cast<const gdcm::ImplicitDataElement&>(element).GetLength()
                        : static_cast<const gdcm::ExplicitDataElement&>(element).GetLength();
    }
    // The element's tag, VR and length: 8 bytes implicit, 12 explicit (OB/OW).
    start += implicit ? 8 : 12;
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(file, ec);
    header.pixelBytes = !ec && present(0x7fe0, 0x0010) && size > start ? size - start : 0;
    const long samples = integer(0x0028, 0x0002, 1);
    const long bits = integer(0x0028, 0x0100, 16);
    const long frames = integer(0x0028, 0x0008, 1);
    if (header.rows > 0 && header.columns > 0 && samples > 0 && bits > 0 && frames > 0)
    {
      header.expectedPixelBytes = static_cast<std::uint64_t>(header.rows) *
        static_cast<std::uint64_t>(header.columns) * static_cast<std::uint64_t>(samples) *
        static_cast<std::uint64_t>(frames) * static_cast<std::uint64_t>((bits + 7) / 8);
    }
  }
  return header;
}

} // namespace vimlop
