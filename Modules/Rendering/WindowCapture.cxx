#include <vimlop/Rendering/WindowCapture.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

namespace vimlop
{

vtkSmartPointer<vtkImageData> captureWindow(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->SetInputBufferTypeToRGB();
  capture->ReadFrontBufferOff(); // the offscreen buffer that was just rendered
  capture->ShouldRerenderOff();
  capture->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(capture->GetOutput());
  // The filter reports the window's position in its extent; pictures start at 0.
  int dims[3];
  image->GetDimensions(dims);
  image->SetExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, 0);
  return image;
}

} // namespace vimlop
