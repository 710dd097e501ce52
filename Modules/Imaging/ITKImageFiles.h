#ifndef vimlop_ITKImageFiles_h
#define vimlop_ITKImageFiles_h

// Private to the Imaging module (not installed): how the readers of CT
// volumes and displacement fields open an image file through ITK, with one
// set of checks made before any voxel is allocated.

#include <itkImageIOBase.h>
#include <itkMacro.h>

#include <exception>
#include <string>

namespace vimlop::detail
{

/// Registers ITK's NIfTI, NRRD, MetaImage and GDCM image IO factories, once
/// (we do not rely on ITK's generated factory lists). Thread-safe.
void registerImageIOs();

/// @brief "NIfTI", "NRRD", "MetaImage" or "DICOM" from the file's extension; "" for others.
std::string imageFormatName(const std::string& path);

/// @brief What a reader expects of an image file, for the checks and their messages.
struct ExpectedImage
{
  /// The thing read, in messages: "CT volume".
  const char* what;
  unsigned components;
  /// Said when the number of components differs: "a scalar CT volume is needed".
  const char* componentsRule;
};

/**
 * @brief Opens an image file and reads its header, refusing what the voxels
 * must not be read from: an NRRD header teem mishandles, fewer than 3
 * dimensions or under 2 voxels along one, a 4-D series, more than 2^31
 * voxels, other component counts, NIfTI or MetaImage data shorter than the
 * header promises.
 * @throws vimlop::Error "'path': problem".
 */
itk::ImageIOBase::Pointer openImageFile(
  const std::string& path, const std::string& format, const ExpectedImage& expected);

/// @brief The first line of ITK's message (or of another exception's
/// what()), without its object address prefix.
std::string itkMessage(const std::exception& e);

} // namespace vimlop::detail

#endif
