#ifndef vimlop_DicomAttributeRules_h
#define vimlop_DicomAttributeRules_h

// Private to the Imaging module (not installed): the values of DICOM
// attributes on which GDCM or ITK's DICOM reader, built with assertions,
// abort the process; DicomFileCheck's walk judges each file by them. Each
// rule returns "" or the problem, worded to follow "element (gggg,eeee) at
// byte N ".

#include <cstdint>
#include <string>

namespace vimlop::detail
{

/// @brief The standard VR of an attribute GDCM's image reading reads as a
/// typed value (gdcm::Attribute asserts on an explicit VR other than the
/// standard's or UN), nullptr for the others: geometry, pixel format,
/// rescale, real-world values, overlays (60xx) and curves (50xx).
const char* typedAttributeVr(std::uint32_t group, std::uint32_t element);

/// @brief The pixel format and rescale of one data set as read so far, with
/// GDCM's values for those not given.
struct DicomPixelFormat
{
  std::uint32_t samplesPerPixel = 1;
  std::uint32_t bitsAllocated = 0; ///< 0: not given (yet)
  std::uint32_t bitsStored = 0;    ///< 0: not given (Bits Allocated then)
  std::uint32_t pixelRepresentation = 0;
  double rescaleSlope = 1.0;
  double rescaleIntercept = 0.0;
};

/// @brief The value `v` of image attribute (0028,element) (Samples per
/// Pixel, Planar Configuration, Bits Allocated, Bits Stored, High Bit, Pixel
/// Representation) against GDCM's pixel format: they come in tag order, so
/// Bits Stored is judged against the Bits Allocated before it, High Bit
/// against Bits Stored. Records it in `format`.
std::string pixelFormatProblem(std::uint32_t element, std::uint32_t v, DicomPixelFormat& format);

/// @brief The retired Recognition Code (0008,0010): GDCM asserts that a file
/// with one is ACR-NEMA 1.0 or 2.0 (DICOM's old name).
std::string recognitionCodeProblem(std::string code);

/// @brief A Rescale Slope or Intercept (DS) as a number into `value`, or the
/// problem (not a finite number).
std::string decimalProblem(std::string text, const char* name, double& value);

/**
 * @brief ITK's DICOM reader aborts when a rescale of whole numbers maps the
 * stored values onto a type GDCM ranks below the stored one (a Slope of 0,
 * say, or 6 of 16 bits doubled): GDCM's choice of that type, redone. Worded
 * as a whole sentence about the file.
 */
std::string rescaleProblem(const DicomPixelFormat& format);

} // namespace vimlop::detail

#endif
