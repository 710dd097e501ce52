// The one translation unit of the Imaging module that instantiates ITK's
// image IO templates (they are heavy to compile). Like every ITK translation
// unit it includes no Eigen: Debian's ITK 5.2 brings its own older Eigen under
// the same include guards, and the two cannot meet in one file.
#include <vimlop/Imaging/CTVolumeIO.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTHeaderChecks.h>
#include <vimlop/Imaging/DicomSeriesGeometry.h>
#include <vimlop/Imaging/ITKImageIOFactories.h>
#include <vimlop/Imaging/InVesaliusProjectReader.h>

#include <itkGDCMImageIO.h>
#include <itkGDCMImageIOFactory.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageIOFactory.h>
#include <itkImageSeriesReader.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIOFactory.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <mutex>
#include <sstream>

namespace vimlop
{

namespace
{

using ImageType = itk::Image<float, 3>;

/// The largest volume VIMLOP reads: 2^31 voxels (8 GiB as float), far above
/// any head CT (a 1024 x 1024 x 2000 scan is 2.1e9).
constexpr std::uint64_t MaxVoxels = std::uint64_t(1) << 31;

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error("'" + path + "': " + problem);
}

std::string lowerCase(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool endsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// ITK's messages span several lines with source locations; keep the gist.
std::string itkMessage(const itk::ExceptionObject& e)
{
  std::string text = e.GetDescription();
  const auto newline = text.find('\n');
  if (newline != std::string::npos)
  {
    text.resize(newline);
  }
  // Drop ITK's "ITK ERROR: NrrdImageIO(0x55d...): " prefix: object addresses
  // mean nothing to the user.
  const auto object = text.find("(0x");
  const auto colon = object == std::string::npos ? std::string::npos : text.find("): ", object);
  if (colon != std::string::npos)
  {
    text.erase(0, colon + 3);
  }
  while (!text.empty() && (text.back() == ':' || text.back() == ' ' || text.back() == '.'))
  {
    text.pop_back();
  }
  return text;
}

} // namespace

void detail::registerImageIOs()
{
  // Explicit registration: we do not rely on ITK's generated factory lists.
  static std::once_flag once;
  std::call_once(once,
    []
    {
      itk::NiftiImageIOFactory::RegisterOneFactory();
      itk::NrrdImageIOFactory::RegisterOneFactory();
      itk::MetaImageIOFactory::RegisterOneFactory();
      itk::GDCMImageIOFactory::RegisterOneFactory();
    });
}

namespace
{

CTVolume toVolume(const ImageType* image)
{
  CTVolume volume;
  const ImageType::RegionType region = image->GetLargestPossibleRegion();
  for (int axis = 0; axis < 3; ++axis)
  {
    volume.dims[axis] = static_cast<int>(region.GetSize(axis));
    volume.spacingMm[axis] = image->GetSpacing()[axis];
    volume.originMm[axis] = image->GetOrigin()[axis];
    for (int row = 0; row < 3; ++row)
    {
      volume.direction[3 * row + axis] = image->GetDirection()(row, axis);
    }
  }
  const float* buffer = image->GetBufferPointer();
  volume.intensities.assign(buffer, buffer + volume.numberOfVoxels());
  return volume;
}

/// The Series Instance UID (0020,000e) stored in a DICOM file, or "".
std::string seriesInstanceUID(const std::string& file)
{
  try
  {
    return readDicomSliceHeader(file).seriesInstanceUID;
  }
  catch (const Error&)
  {
    return std::string();
  }
}

CTVolume readDicomSeries(const std::string& folder, const std::string& seriesUID)
{
  // Series details split a series whose slices differ in size or orientation
  // (scout images, say); each group is named by the series UID plus details.
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(true);
  names->SetDirectory(folder);
  const std::vector<std::string> groups = names->GetSeriesUIDs();
  if (groups.empty())
  {
    fail(folder, "the folder holds no DICOM series");
  }
  std::string chosen;
  size_t most = 0;
  for (const std::string& group : groups)
  {
    const std::vector<std::string> files = names->GetFileNames(group);
    const bool wanted = seriesUID.empty() || seriesInstanceUID(files.front()) == seriesUID;
    if (wanted && files.size() > most)
    {
      most = files.size();
      chosen = group;
    }
  }
  if (chosen.empty())
  {
    fail(folder, "no DICOM series with UID '" + seriesUID + "' in the folder");
  }
  std::vector<std::string> warnings;
  if (groups.size() > 1 && seriesUID.empty())
  {
    std::ostringstream msg;
    msg << "the folder holds " << groups.size() << " DICOM series; read the largest ("
        << seriesInstanceUID(names->GetFileNames(chosen).front()) << ", " << most
        << " slices); choose another by its series UID";
    warnings.push_back(msg.str());
  }
  // Judge every slice's header before ITK makes a volume of them: its series
  // reader assumes one orientation and even steps, and fills what is missing.
  std::vector<DicomSliceHeader> headers;
  std::vector<std::string> files;
  try
  {
    for (const std::string& file : names->GetFileNames(chosen))
    {
      headers.push_back(readDicomSliceHeader(file));
    }
    for (std::size_t index : checkDicomSeriesGeometry(headers).order)
    {
      files.push_back(headers[index].file);
    }
  }
  catch (const Error& e)
  {
    fail(folder, e.what());
  }
  auto reader = itk::ImageSeriesReader<ImageType>::New();
  reader->SetImageIO(itk::GDCMImageIO::New());
  reader->SetFileNames(files);
  try
  {
    reader->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    fail(folder, "cannot read the DICOM series (" + itkMessage(e) + ")");
  }
  CTVolume volume = toVolume(reader->GetOutput());
  volume.format = "DICOM series";
  volume.warnings = std::move(warnings);
  const DicomSliceHeader& first = headers.front();
  for (const auto& [key, value] :
    { std::pair<const char*, std::string>{ "series_instance_uid", first.seriesInstanceUID },
      { "study_instance_uid", first.studyInstanceUID }, { "patient_id", first.patientID } })
  {
    if (!value.empty())
    {
      volume.identity[key] = value;
    }
  }
  return volume;
}

std::string formatName(const std::string& lowerPath)
{
  if (endsWith(lowerPath, ".nii") || endsWith(lowerPath, ".nii.gz"))
  {
    return "NIfTI";
  }
  if (endsWith(lowerPath, ".nrrd") || endsWith(lowerPath, ".nhdr"))
  {
    return "NRRD";
  }
  if (endsWith(lowerPath, ".mha") || endsWith(lowerPath, ".mhd"))
  {
    return "MetaImage";
  }
  if (endsWith(lowerPath, ".dcm"))
  {
    return "DICOM";
  }
  return "";
}

CTVolume readImageFile(const std::string& path, const std::string& format)
{
  if (format == "NRRD")
  {
    detail::checkNrrdHeader(path); // before teem parses it
  }
  itk::ImageIOBase::Pointer io =
    itk::ImageIOFactory::CreateImageIO(path.c_str(), itk::ImageIOFactory::IOFileModeEnum::ReadMode);
  if (!io)
  {
    fail(path, "not a readable " + format + " file");
  }
  io->SetFileName(path);
  try
  {
    io->ReadImageInformation();
  }
  catch (const itk::ExceptionObject& e)
  {
    fail(path, "cannot read the " + format + " header (" + itkMessage(e) + ")");
  }
  const unsigned dimensions = io->GetNumberOfDimensions();
  std::string size;
  for (unsigned axis = 0; axis < std::min(dimensions, 3u); ++axis)
  {
    size += (axis ? " x " : "") + std::to_string(io->GetDimensions(axis));
  }
  if (dimensions < 3)
  {
    fail(path, "the image is 2-D (" + size + " pixels); a 3-D CT volume is needed");
  }
  if (io->GetDimensions(0) < 2 || io->GetDimensions(1) < 2 || io->GetDimensions(2) < 2)
  {
    // One voxel thick along an axis is a slice (or a point), not a volume.
    fail(
      path, "the image is " + size + " voxels; a 3-D CT volume needs at least 2 along each axis");
  }
  if (dimensions > 3 && io->GetDimensions(3) > 1)
  {
    fail(path, "the image is 4-D (a time series); a 3-D CT volume is needed");
  }
  // Refuse before allocating: a header can promise far more than any CT.
  std::uint64_t voxels = 1;
  for (unsigned axis = 0; axis < std::min(dimensions, 3u); ++axis)
  {
    voxels *= std::max<std::uint64_t>(io->GetDimensions(axis), 1);
    if (voxels > MaxVoxels)
    {
      break;
    }
  }
  if (voxels > MaxVoxels)
  {
    fail(path,
      "the header promises more than " + std::to_string(MaxVoxels) +
        " voxels; refusing to allocate it");
  }
  if (io->GetNumberOfComponents() != 1)
  {
    fail(path,
      "the image has " + std::to_string(io->GetNumberOfComponents()) +
        " components per voxel; a scalar CT volume is needed");
  }
  if (endsWith(lowerCase(path), ".nii"))
  {
    detail::checkNiftiLength(path, io->GetImageSizeInBytes());
  }
  if (format == "MetaImage")
  {
    detail::checkMetaImageData(path, io->GetImageSizeInBytes());
  }
  auto reader = itk::ImageFileReader<ImageType>::New();
  reader->SetFileName(path);
  reader->SetImageIO(io);
  try
  {
    reader->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    fail(path, "cannot read the image data (" + itkMessage(e) + ")");
  }
  CTVolume volume = toVolume(reader->GetOutput());
  volume.format = format;
  return volume;
}

} // namespace

bool isCTVolumePath(const std::string& path)
{
  const std::string lower = lowerCase(path);
  return std::filesystem::is_directory(path) || endsWith(lower, ".inv3") ||
    !formatName(lower).empty();
}

bool isWritableCTVolumePath(const std::string& path)
{
  const std::string format = formatName(lowerCase(path));
  return !format.empty() && format != "DICOM";
}

namespace
{

/// Geometry no CT has, refused whatever the format: ITK reads a spacing of
/// 1e300 mm or an origin of 1e308 mm as given, and they overflow later.
void checkGeometry(const std::string& path, const CTVolume& volume)
{
  constexpr double maxSpacingMm = 100.0;
  constexpr double maxOriginMm = 1e6;
  std::ostringstream problem;
  problem << std::setprecision(6);
  const auto& s = volume.spacingMm;
  const auto& o = volume.originMm;
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
    const auto& d = volume.direction;
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

CTVolume readAnyFormat(const std::string& path, const std::string& dicomSeriesUID)
{
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
  {
    fail(path, "no such file or folder");
  }
  detail::registerImageIOs();
  if (std::filesystem::is_directory(path, ec))
  {
    return readDicomSeries(path, dicomSeriesUID);
  }
  const std::string lower = lowerCase(path);
  if (endsWith(lower, ".inv3"))
  {
    return readInVesaliusProject(path);
  }
  const std::string format = formatName(lower);
  if (format.empty())
  {
    fail(path,
      "unsupported CT file type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd, .dcm, "
      ".inv3 or a DICOM folder)");
  }
  return readImageFile(path, format);
}

} // namespace

CTVolume readCTVolume(const std::string& path, const std::string& dicomSeriesUID)
{
  CTVolume volume = readAnyFormat(path, dicomSeriesUID);
  checkGeometry(path, volume);
  return volume;
}

void writeCTVolume(const CTVolume& volume, const std::string& path)
{
  if (!isWritableCTVolumePath(path))
  {
    fail(path, "unsupported output type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd)");
  }
  if (volume.intensities.size() != volume.numberOfVoxels() || volume.numberOfVoxels() == 0)
  {
    fail(path, "the volume to write is empty or inconsistent");
  }
  detail::registerImageIOs();
  auto image = ImageType::New();
  ImageType::SizeType size;
  ImageType::SpacingType spacing;
  ImageType::PointType origin;
  ImageType::DirectionType direction;
  for (int axis = 0; axis < 3; ++axis)
  {
    size[axis] = static_cast<itk::SizeValueType>(volume.dims[axis]);
    spacing[axis] = volume.spacingMm[axis];
    origin[axis] = volume.originMm[axis];
    for (int row = 0; row < 3; ++row)
    {
      direction(row, axis) = volume.direction[3 * row + axis];
    }
  }
  image->SetRegions(ImageType::RegionType(size));
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  image->Allocate();
  std::copy(volume.intensities.begin(), volume.intensities.end(), image->GetBufferPointer());
  auto writer = itk::ImageFileWriter<ImageType>::New();
  writer->SetFileName(path);
  writer->SetInput(image);
  writer->SetUseCompression(true);
  try
  {
    writer->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    fail(path, "cannot write the image (" + itkMessage(e) + ")");
  }
}

} // namespace vimlop
