#ifndef vimlop_ImageFileHeader_h
#define vimlop_ImageFileHeader_h

#include <cstdint>
#include <string>

namespace vimlop
{

/// @brief The size an image file's header declares, read without decoding
/// the pixels. `known` is false for formats not read here (TIFF) and for a
/// header too short or damaged to say; the decoder then judges the file.
struct ImageFileHeader
{
  std::uint64_t widthPx = 0;
  std::uint64_t heightPx = 0;
  bool known = false;
};

/**
 * @brief Reads the width and height of a PNG (IHDR), JPEG (the first
 * start-of-frame marker) or BMP (the info header) file.
 *
 * A picture decodes to width x height x channels bytes whatever its file
 * size: a 380 KB PNG can promise 2 GB. FrameSequence checks the promise
 * before it lets OpenCV decode anything.
 */
ImageFileHeader readImageFileHeader(const std::string& file);

} // namespace vimlop

#endif
