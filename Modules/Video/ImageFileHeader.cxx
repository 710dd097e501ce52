#include "ImageFileHeader.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>

namespace vimlop
{

namespace
{

std::uint64_t bigEndian(const unsigned char* p, int bytes)
{
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i)
  {
    v = v << 8 | p[i];
  }
  return v;
}

std::uint64_t littleEndian(const unsigned char* p, int bytes)
{
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i)
  {
    v = v << 8 | p[i];
  }
  return v;
}

/// JPEG: walk the marker segments to the first start of frame (SOF0..SOF15
/// but DHT, JPG and DAC, which share the range).
ImageFileHeader jpegHeader(std::ifstream& in)
{
  ImageFileHeader header;
  in.seekg(2);
  for (int segments = 0; segments < 10000; ++segments)
  {
    unsigned char marker[4];
    if (!in.read(reinterpret_cast<char*>(marker), 4) || marker[0] != 0xff)
    {
      return header;
    }
    const int type = marker[1];
    const std::uint64_t length = bigEndian(marker + 2, 2);
    if (type >= 0xc0 && type <= 0xcf && type != 0xc4 && type != 0xc8 && type != 0xcc)
    {
      unsigned char frame[5];
      if (!in.read(reinterpret_cast<char*>(frame), 5))
      {
        return header;
      }
      header.heightPx = bigEndian(frame + 1, 2);
      header.widthPx = bigEndian(frame + 3, 2);
      header.known = true;
      return header;
    }
    if (length < 2)
    {
      return header;
    }
    in.seekg(static_cast<std::streamoff>(length - 2), std::ios::cur);
  }
  return header;
}

} // namespace

ImageFileHeader readImageFileHeader(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 26> start{};
  if (!in.read(reinterpret_cast<char*>(start.data()), start.size()))
  {
    in.clear();
  }
  const std::streamsize got = in.gcount();
  ImageFileHeader header;
  const unsigned char png[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
  if (got >= 24 && std::equal(png, png + 8, start.begin()))
  {
    header.widthPx = bigEndian(&start[16], 4);
    header.heightPx = bigEndian(&start[20], 4);
    header.known = true;
  }
  else if (got >= 4 && start[0] == 0xff && start[1] == 0xd8)
  {
    in.clear();
    header = jpegHeader(in);
  }
  else if (got >= 26 && start[0] == 'B' && start[1] == 'M')
  {
    if (littleEndian(&start[14], 4) == 12)
    {
      // BITMAPCOREHEADER (OS/2): unsigned 16-bit width and height.
      header.widthPx = littleEndian(&start[18], 2);
      header.heightPx = littleEndian(&start[20], 2);
      header.known = true;
      return header;
    }
    // BITMAPINFOHEADER and later: signed 32-bit width and height (negative: top-down).
    header.widthPx = static_cast<std::uint64_t>(
      std::llabs(static_cast<std::int32_t>(littleEndian(&start[18], 4))));
    header.heightPx = static_cast<std::uint64_t>(
      std::llabs(static_cast<std::int32_t>(littleEndian(&start[22], 4))));
    header.known = true;
  }
  return header;
}

} // namespace vimlop
