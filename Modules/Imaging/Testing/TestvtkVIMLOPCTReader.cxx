#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Imaging/vtkVIMLOPCTReader.h>

#include <gtest/gtest.h>

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>

using namespace vimlop;

namespace
{

/// Collects the error events of a VTK object instead of printing them.
struct ErrorCatcher : vtkCommand
{
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Message = static_cast<const char*>(data);
  }
  std::string Message;
};

} // namespace

TEST(vtkVIMLOPCTReader, OutputsImageDataWithGeometry)
{
  CTVolume v;
  v.dims = { 4, 3, 2 };
  v.spacingMm = { 0.5, 0.6, 0.7 };
  v.originMm = { 1, 2, 3 };
  v.direction = { 0, 1, 0, -1, 0, 0, 0, 0, 1 }; // axes swapped in-plane
  v.intensities.resize(24);
  for (int i = 0; i < 24; ++i)
  {
    v.intensities[i] = static_cast<float>(10 * i);
  }
  const std::string path = std::string(VIMLOP_TEST_OUTPUT_DIR) + "/reader.nrrd";
  writeCTVolume(v, path);

  vtkNew<vtkVIMLOPCTReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 4);
  EXPECT_EQ(dims[2], 2);
  EXPECT_NEAR(image->GetSpacing()[1], 0.6, 1e-9);
  EXPECT_NEAR(image->GetOrigin()[2], 3.0, 1e-9);
  EXPECT_NEAR(image->GetDirectionMatrix()->GetElement(1, 0), -1.0, 1e-9);
  EXPECT_STREQ(reader->GetFormatName(), "NRRD");
  EXPECT_EQ(image->GetScalarRange()[1], 230.0);
  // VTK applies the direction when mapping indices to physical points.
  double physical[3];
  image->TransformIndexToPhysicalPoint(1, 0, 0, physical);
  const std::array<double, 3> expected = v.indexToPhysical({ 1, 0, 0 });
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_NEAR(physical[i], expected[i], 1e-9);
  }
  EXPECT_STREQ(image->GetPointData()->GetScalars()->GetName(), "Intensity");
}

TEST(vtkVIMLOPCTReader, ReportsErrorsThroughVTK)
{
  vtkNew<vtkVIMLOPCTReader> reader;
  vtkNew<ErrorCatcher> catcher;
  reader->AddObserver(vtkCommand::ErrorEvent, catcher);
  reader->SetFileName("/nonexistent/ct.nii.gz");
  reader->Update();
  EXPECT_NE(
    catcher->Message.find("'/nonexistent/ct.nii.gz': no such file or folder"), std::string::npos)
    << catcher->Message;
}
