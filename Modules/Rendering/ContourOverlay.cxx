#include <vimlop/Rendering/ContourOverlay.h>

#include <vimlop/Core/Error.h>

#include <vtkImageData.h>

#include <cmath>
#include <cstring>
#include <string>

namespace vimlop
{

namespace
{

void checkSize(vtkImageData* image, int widthPx, int heightPx, const char* what)
{
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] != widthPx || dims[1] != heightPx)
  {
    throw Error(std::string(what) + " is " + std::to_string(dims[0]) + " x " +
      std::to_string(dims[1]) + " pixels; the frame is " + std::to_string(widthPx) + " x " +
      std::to_string(heightPx));
  }
}

} // namespace

vtkSmartPointer<vtkImageData> composeContourOverlay(int widthPx, int heightPx, vtkImageData* frame,
  vtkImageData* modelContours, const std::vector<ContourPoint>& videoContour)
{
  auto overlay = vtkSmartPointer<vtkImageData>::New();
  overlay->SetDimensions(widthPx, heightPx, 1);
  overlay->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* out = static_cast<unsigned char*>(overlay->GetScalarPointer());
  const auto n = static_cast<size_t>(widthPx) * heightPx;
  if (frame)
  {
    checkSize(frame, widthPx, heightPx, "the frame picture");
    if (frame->GetNumberOfScalarComponents() != 3 || frame->GetScalarType() != VTK_UNSIGNED_CHAR)
    {
      throw Error("the frame picture must be RGB with 8 bits per channel");
    }
    std::memcpy(out, frame->GetScalarPointer(), 3 * n);
  }
  else
  {
    std::memset(out, 40, 3 * n);
  }
  if (modelContours)
  {
    checkSize(modelContours, widthPx, heightPx, "the contour mask");
    const auto* mask = static_cast<const unsigned char*>(modelContours->GetScalarPointer());
    const int stride = modelContours->GetNumberOfScalarComponents();
    for (size_t i = 0; i < n; ++i)
    {
      if (mask[stride * i] != 0)
      {
        out[3 * i] = 0;
        out[3 * i + 1] = 255;
        out[3 * i + 2] = 0;
      }
    }
  }
  for (const ContourPoint& c : videoContour)
  {
    const long u = std::lround(c.pixel.x());
    const long v = std::lround(c.pixel.y());
    if (u < 0 || v < 0 || u >= widthPx || v >= heightPx)
    {
      continue;
    }
    const size_t i = static_cast<size_t>(heightPx - 1 - v) * widthPx + static_cast<size_t>(u);
    std::memset(out + 3 * i, 255, 3);
  }
  return overlay;
}

vtkSmartPointer<vtkImageData> placeSideBySide(
  const std::vector<vtkSmartPointer<vtkImageData>>& pictures, int gapPx)
{
  if (pictures.empty())
  {
    throw Error("side by side: no pictures");
  }
  int dims[3];
  pictures.front()->GetDimensions(dims);
  const int height = dims[1];
  int width = 0;
  for (const auto& picture : pictures)
  {
    picture->GetDimensions(dims);
    if (dims[1] != height || picture->GetNumberOfScalarComponents() != 3)
    {
      throw Error("side by side: the pictures must be RGB and of the same height");
    }
    width += dims[0];
  }
  width += gapPx * static_cast<int>(pictures.size() - 1);
  auto combined = vtkSmartPointer<vtkImageData>::New();
  combined->SetDimensions(width, height, 1);
  combined->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* out = static_cast<unsigned char*>(combined->GetScalarPointer());
  std::memset(out, 0, 3 * static_cast<size_t>(width) * height);
  int left = 0;
  for (const auto& picture : pictures)
  {
    picture->GetDimensions(dims);
    const auto* in = static_cast<const unsigned char*>(picture->GetScalarPointer());
    for (int row = 0; row < height; ++row)
    {
      std::memcpy(out + 3 * (static_cast<size_t>(row) * width + left),
        in + 3 * static_cast<size_t>(row) * dims[0], 3 * static_cast<size_t>(dims[0]));
    }
    left += dims[0] + gapPx;
  }
  return combined;
}

} // namespace vimlop
