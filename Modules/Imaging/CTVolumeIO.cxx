// The one translation unit of the Imaging module that instantiates ITK's
// image IO templates (they are heavy to compile). Like every ITK translation
// unit it includes no Eigen: Debian's ITK 5.2 brings its own older Eigen under
// the same include guards, and the two cannot meet in one file.
#include <vimlop/Imaging/CTVolumeIO.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/CTHeaderChecks.h>
#include <vimlop/Imaging/DicomFileCheck.h>
#include <vimlop/Imaging/DicomSeriesGeometry.h>
#include <vimlop/Imaging/ITKImageFiles.h>
#include <vimlop/Imaging/InVesaliusProjectReader.h>

#include <itkGDCMImageIO.h>
#include <itkGDCMImageIOFactory.h>
#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageSeriesReader.h>
#include <itkMetaImageIO.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIO.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIO.h>
#include <itkNrrdImageIOFactory.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <map>
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

bool endsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace

/// ITK's messages span several lines with source locations; keep the gist.
std::string detail::itkMessage(const std::exception& e)
{
  const auto* itkError = dynamic_cast<const itk::ExceptionObject*>(&e);
  std::string text = itkError ? itkError->GetDescription() : e.what();
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

/// The group a slice belongs to: its series, and (as GDCM's "series
/// details" did) its orientation and size, so that scout images filed under
/// the series UID of the scan form a group of their own.
std::string seriesGroupKey(const DicomSliceHeader& h)
{
  std::ostringstream key;
  key << h.seriesInstanceUID << " " << h.rows << "x" << h.columns << std::fixed
      << std::setprecision(2);
  for (double v : h.orientation)
  {
    key << " " << (std::abs(v) < 0.005 ? 0.0 : v);
  }
  return key.str();
}

CTVolume readDicomSeries(const std::string& folder, const CTReadOptions& options)
{
  const std::string& seriesUID = options.dicomSeriesUID;
  // Every file is judged by VIMLOP before GDCM parses it (GDCM aborts or
  // allocates gigabytes on some broken files), so the folder is not handed
  // to GDCM's scanner: files without the DICOM preamble are passed over,
  // the others walked, their headers read and grouped here.
  std::vector<std::string> paths;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
  {
    if (entry.is_regular_file(ec))
    {
      paths.push_back(entry.path().string());
    }
  }
  std::sort(paths.begin(), paths.end());
  std::map<std::string, std::vector<DicomSliceHeader>> groups;
  int passedOver = 0;
  for (const std::string& file : paths)
  {
    if (!detail::hasDicomPreamble(file))
    {
      ++passedOver;
      continue;
    }
    // A broken DICOM file is refused naming it, rather than passed over.
    DicomSliceHeader header = readDicomSliceHeader(file);
    if (header.rows == 0 || header.columns == 0)
    {
      ++passedOver; // a DICOMDIR, a report: no image
      continue;
    }
    groups[seriesGroupKey(header)].push_back(std::move(header));
  }
  if (groups.empty())
  {
    throwFileError(folder,
      "the folder holds no DICOM series" +
        (passedOver == 0 ? std::string()
                         : " (" + std::to_string(passedOver) +
              " files without 'DICM' at byte 128 or without pixels were passed over)"));
  }
  const std::vector<DicomSliceHeader>* chosen = nullptr;
  for (const auto& [key, slices] : groups)
  {
    const bool wanted = seriesUID.empty() || slices.front().seriesInstanceUID == seriesUID;
    if (wanted && (!chosen || slices.size() > chosen->size()))
    {
      chosen = &slices;
    }
  }
  if (!chosen)
  {
    throwFileError(folder, "no DICOM series with UID '" + seriesUID + "' in the folder");
  }
  std::vector<std::string> warnings;
  if (groups.size() > 1 && seriesUID.empty())
  {
    std::ostringstream msg;
    msg << "the folder holds " << groups.size() << " DICOM series; read the largest ("
        << chosen->front().seriesInstanceUID << ", " << chosen->size()
        << " slices); choose another by its series UID";
    warnings.push_back(msg.str());
  }
  // Judge every slice's header before ITK makes a volume of them: its series
  // reader assumes one orientation and even steps, and fills what is missing.
  const std::vector<DicomSliceHeader>& headers = *chosen;
  std::vector<std::string> files;
  DicomSeriesLayout layout;
  try
  {
    layout = checkDicomSeriesGeometry(headers, DicomSeriesTolerances(),
      options.resampleIrregularSeries ? IrregularSeries::Resample : IrregularSeries::Refuse);
    for (std::size_t index : layout.order)
    {
      files.push_back(headers[index].file);
    }
  }
  catch (const Error& e)
  {
    throwFileError(folder, e.what());
  }
  auto reader = itk::ImageSeriesReader<ImageType>::New();
  reader->SetImageIO(itk::GDCMImageIO::New());
  reader->SetFileNames(files);
  try
  {
    reader->Update();
  }
  catch (const std::exception& e) // ITK also throws std::length_error, std::bad_alloc
  {
    throwFileError(folder, "cannot read the DICOM series (" + detail::itkMessage(e) + ")");
  }
  CTVolume volume = toVolume(reader->GetOutput());
  if (!layout.irregularities.empty())
  {
    const DicomSliceHeader& lowest = headers[layout.order.front()];
    volume = resampleDicomStack(volume, layout, lowest);
    std::ostringstream what;
    what << std::fixed << std::setprecision(2) << "resampled onto a regular grid of "
         << volume.dims[2] << " slices " << layout.sliceStepMm << " mm apart along the normal of '"
         << lowest.file << "', as asked, from an irregular series: ";
    for (std::size_t i = 0; i < layout.irregularities.size(); ++i)
    {
      what << (i ? "; " : "") << layout.irregularities[i];
    }
    what << ". Voxels beside the slices' pixels are -1024 HU (air)";
    warnings.push_back(what.str());
    volume.identity["resampled"] = what.str();
  }
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

} // namespace

std::string detail::imageFormatName(const std::string& path)
{
  const std::string lowerPath = lowerCase(path);
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

namespace
{

itk::ImageIOBase::Pointer openCheckedImageFile(
  const std::string& path, const std::string& format, const detail::ExpectedImage& expected)
{
  if (format == "NRRD")
  {
    detail::checkNrrdHeader(path); // before teem parses it
  }
  if (format == "DICOM")
  {
    detail::checkDicomPart10(path); // before GDCM parses it
  }
  if (format == "MetaImage")
  {
    detail::checkMetaImageData(path, 0); // the header's text, before MetaIO parses it
  }
  // Before ITK takes the orientation's SVD; ITK 5.2 reads NIfTI-1 only.
  const int niftiVersion = format == "NIfTI" ? detail::checkNiftiHeader(path) : 0;
  // The reader of the format the extension names, not ITK's factory: the
  // factory asks every reader whether it can read the file, and GDCM's
  // answer parses a file of any name as DICOM (and aborts on some).
  itk::ImageIOBase::Pointer io;
  if (format == "NIfTI")
  {
    io = itk::NiftiImageIO::New();
  }
  else if (format == "NRRD")
  {
    io = itk::NrrdImageIO::New();
  }
  else if (format == "MetaImage")
  {
    io = itk::MetaImageIO::New();
  }
  else
  {
    io = itk::GDCMImageIO::New();
  }
  if (!io->CanReadFile(path.c_str()))
  {
    throwFileError(path,
      niftiVersion == 2
        ? "a NIfTI-2 file, which this build's ITK (" + std::string(ITK_VERSION_STRING) +
          ") does not read; save the volume as NIfTI-1 (.nii, .nii.gz), NRRD or MetaImage"
        : "not a readable " + format + " file");
  }
  io->SetFileName(path);
  try
  {
    io->ReadImageInformation();
  }
  catch (const itk::ExceptionObject& e)
  {
    throwFileError(path, "cannot read the " + format + " header (" + detail::itkMessage(e) + ")");
  }
  const unsigned dimensions = io->GetNumberOfDimensions();
  std::string size;
  for (unsigned axis = 0; axis < std::min(dimensions, 3u); ++axis)
  {
    size += (axis ? " x " : "") + std::to_string(io->GetDimensions(axis));
  }
  if (dimensions < 3)
  {
    throwFileError(
      path, "the image is 2-D (" + size + " pixels); a 3-D " + expected.what + " is needed");
  }
  if (io->GetDimensions(0) < 2 || io->GetDimensions(1) < 2 || io->GetDimensions(2) < 2)
  {
    // One voxel thick along an axis is a slice (or a point), not a volume.
    throwFileError(path,
      "the image is " + size + " voxels; a 3-D " + expected.what +
        " needs at least 2 along each axis");
  }
  if (dimensions > 3 && io->GetDimensions(3) > 1)
  {
    throwFileError(
      path, "the image is 4-D (a time series); a 3-D " + std::string(expected.what) + " is needed");
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
    throwFileError(path,
      "the header promises more than " + std::to_string(MaxVoxels) +
        " voxels; refusing to allocate it");
  }
  if (io->GetComponentType() == itk::IOComponentEnum::UNKNOWNCOMPONENTTYPE)
  {
    throwFileError(path, "the header names no voxel type " + format + " files have");
  }
  if (io->GetNumberOfComponents() != expected.components)
  {
    throwFileError(path,
      "the image has " + std::to_string(io->GetNumberOfComponents()) + " components per voxel; " +
        expected.componentsRule);
  }
  const std::uint64_t voxelBytes = io->GetImageSizeInBytes();
  if (endsWith(lowerCase(path), ".nii"))
  {
    detail::checkNiftiLength(path, voxelBytes);
  }
  if (endsWith(lowerCase(path), ".nii.gz"))
  {
    std::error_code ec;
    detail::checkCompressedBound(path, std::filesystem::file_size(path, ec), voxelBytes);
  }
  if (format == "NRRD")
  {
    detail::checkNrrdData(path, voxelBytes);
  }
  if (format == "MetaImage")
  {
    detail::checkMetaImageData(path, voxelBytes);
  }
  return io;
}

} // namespace

itk::ImageIOBase::Pointer detail::openImageFile(
  const std::string& path, const std::string& format, const ExpectedImage& expected)
{
  // ITK throws from more places than ReadImageInformation (the image IO
  // factories' CanReadFile, the size of an unknown type): none may escape.
  try
  {
    return openCheckedImageFile(path, format, expected);
  }
  catch (const Error&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    throwFileError(path, "cannot read the " + format + " header (" + detail::itkMessage(e) + ")");
  }
}

namespace
{

CTVolume readImageFile(const std::string& path, const std::string& format)
{
  itk::ImageIOBase::Pointer io =
    detail::openImageFile(path, format, { "CT volume", 1, "a scalar CT volume is needed" });
  auto reader = itk::ImageFileReader<ImageType>::New();
  reader->SetFileName(path);
  reader->SetImageIO(io);
  try
  {
    reader->Update();
  }
  catch (const std::exception& e) // ITK also throws std::length_error, std::bad_alloc
  {
    throwFileError(path, "cannot read the image data (" + detail::itkMessage(e) + ")");
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
    !detail::imageFormatName(lower).empty();
}

bool isWritableCTVolumePath(const std::string& path)
{
  const std::string format = detail::imageFormatName(path);
  return !format.empty() && format != "DICOM";
}

namespace
{

CTVolume readAnyFormat(const std::string& path, const CTReadOptions& options)
{
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
  {
    throwFileError(path, "no such file or folder");
  }
  detail::registerImageIOs();
  if (std::filesystem::is_directory(path, ec))
  {
    return readDicomSeries(path, options);
  }
  const std::string lower = lowerCase(path);
  if (endsWith(lower, ".inv3"))
  {
    return readInVesaliusProject(path);
  }
  const std::string format = detail::imageFormatName(lower);
  if (format.empty())
  {
    throwFileError(path,
      "unsupported CT file type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd, .dcm, "
      ".inv3 or a DICOM folder)");
  }
  return readImageFile(path, format);
}

} // namespace

CTVolume readCTVolume(const std::string& path, const CTReadOptions& options)
{
  CTVolume volume = readAnyFormat(path, options);
  detail::checkGridGeometry(path, volume.spacingMm, volume.originMm, volume.direction);
  return volume;
}

void writeCTVolume(const CTVolume& volume, const std::string& path)
{
  if (!isWritableCTVolumePath(path))
  {
    throwFileError(
      path, "unsupported output type (expected .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd)");
  }
  if (volume.intensities.size() != volume.numberOfVoxels() || volume.numberOfVoxels() == 0)
  {
    throwFileError(path, "the volume to write is empty or inconsistent");
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
    throwFileError(path, "cannot write the image (" + detail::itkMessage(e) + ")");
  }
}

} // namespace vimlop
