#include <vimlop/Rendering/PNGImageIO.h>

#include <vimlop/Core/FileError.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>

#include <filesystem>

namespace vimlop
{

void writePNG(vtkImageData* image, const std::string& path)
{
  if (!image || image->GetScalarType() != VTK_UNSIGNED_CHAR)
  {
    throwFileError(path, "only unsigned char images can be written as PNG");
  }
  vtkNew<vtkPNGWriter> writer;
  // zlib's fastest level: the pictures are the same (PNG is lossless), written
  // in a fraction of the time of VTK's default level 5, a little larger.
  writer->SetCompressionLevel(1);
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
  std::error_code ec;
  if (writer->GetErrorCode() != 0 || !std::filesystem::is_regular_file(path, ec))
  {
    throwFileError(path, "cannot write the picture");
  }
}

vtkSmartPointer<vtkImageData> readPNG(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    throwFileError(path, "no such file");
  }
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    throwFileError(path, "not a PNG picture");
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* input = reader->GetOutput();
  const int components = input->GetNumberOfScalarComponents();
  if (input->GetScalarType() != VTK_UNSIGNED_CHAR || components < 1 || components > 4)
  {
    throwFileError(path, "only 8-bit PNG pictures are supported");
  }
  int dims[3];
  input->GetDimensions(dims);
  auto rgb = vtkSmartPointer<vtkImageData>::New();
  rgb->SetDimensions(dims[0], dims[1], 1);
  rgb->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  const auto* in = static_cast<const unsigned char*>(input->GetScalarPointer());
  auto* out = static_cast<unsigned char*>(rgb->GetScalarPointer());
  const auto n = static_cast<size_t>(dims[0]) * dims[1];
  for (size_t i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      // Grey (1 or 2 components) repeats its first channel.
      out[3 * i + c] = in[components * i + (components >= 3 ? c : 0)];
    }
  }
  return rgb;
}

} // namespace vimlop
