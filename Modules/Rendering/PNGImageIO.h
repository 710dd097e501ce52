#ifndef vimlop_PNGImageIO_h
#define vimlop_PNGImageIO_h

#include "VIMLOPRenderingModule.h"

#include <vtkSmartPointer.h>

#include <string>

class vtkImageData;

/**
 * @file PNGImageIO.h
 * @brief Pictures in and out as PNG files, with VTK (vtkPNGReader, vtkPNGWriter).
 *
 * Images are VTK images: row 0 is the bottom row of the picture.
 */

namespace vimlop
{

/**
 * @brief Writes an unsigned char image (1, 3 or 4 components) as a PNG file
 * (zlib compression level 1: fast, lossless like every level).
 * @throws vimlop::Error naming the file if it cannot be written.
 */
VIMLOPRENDERING_EXPORT void writePNG(vtkImageData* image, const std::string& path);

/**
 * @brief Reads a PNG file as an RGB unsigned char image (grey is repeated in
 * the three channels, alpha is dropped).
 * @throws vimlop::Error naming the file if it is missing or not a PNG picture.
 */
VIMLOPRENDERING_EXPORT vtkSmartPointer<vtkImageData> readPNG(const std::string& path);

} // namespace vimlop

#endif
