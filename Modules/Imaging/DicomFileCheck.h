#ifndef vimlop_DicomFileCheck_h
#define vimlop_DicomFileCheck_h

// Private to the Imaging module (not installed): a DICOM file judged before
// GDCM parses it. Throws vimlop::Error "'path': problem". GDCM-free: plain
// file reading.

#include <string>

namespace vimlop::detail
{

/// @brief The file has 'DICM' at byte 128, as DICOM Part 10 files do.
bool hasDicomPreamble(const std::string& path);

/**
 * @brief A DICOM Part 10 file, walked element by element as GDCM will read
 * it, before GDCM does (built with assertions, it aborts the process on an
 * invalid VR, and it allocates an element's declared length before reading
 * it): 'DICM' at byte 128, valid VRs, every declared length within what its
 * file or sequence has left, items closed by their delimiters, sequences
 * nested at most 16 deep, the pixel format values GDCM asserts on (samples
 * per pixel, bits allocated, stored and high bit, pixel representation) and a
 * little-endian, not deflated, transfer syntax.
 */
void checkDicomPart10(const std::string& path);

} // namespace vimlop::detail

#endif
