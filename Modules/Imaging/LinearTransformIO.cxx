// ITK translation unit: no Eigen here (see CTVolume.h).
#include <vimlop/Imaging/LinearTransformIO.h>

#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/ITKImageFiles.h>

#include <itkAffineTransform.h>
#include <itkCompositeTransform.h>
#include <itkHDF5TransformIOFactory.h>
#include <itkMatlabTransformIOFactory.h>
#include <itkTransformFactoryBase.h>
#include <itkTransformFileReader.h>
#include <itkTransformFileWriter.h>
#include <itkTxtTransformIOFactory.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <mutex>

namespace vimlop
{

namespace
{

/// ITK's transform IO factories and transform classes, registered once: we do
/// not rely on ITK's generated factory lists (as for images, ITKImageFiles.h).
void registerTransformIOs()
{
  static std::once_flag once;
  std::call_once(once,
    []
    {
      itk::TxtTransformIOFactory::RegisterOneFactory();
      itk::HDF5TransformIOFactory::RegisterOneFactory();
      itk::MatlabTransformIOFactory::RegisterOneFactory();
      itk::TransformFactoryBase::RegisterDefaultTransforms();
    });
}

bool allFinite(const AffineMatrix4& pointMap)
{
  return std::all_of(pointMap.begin(), pointMap.end(), [](double v) { return std::isfinite(v); });
}

/// What the reader returns: the map, refused when a value is not finite.
AffineMatrix4 finiteOrFail(const AffineMatrix4& pointMap, const std::string& path)
{
  if (!allFinite(pointMap))
  {
    throwFileError(path, "holds a transform with a value that is not finite");
  }
  return pointMap;
}

const char* const extensionsText = ".tfm, .txt, .h5, .hdf5 or .mat";

} // namespace

bool isLinearTransformPath(const std::string& path)
{
  const std::string ext = lowerCaseExtension(path);
  return ext == ".tfm" || ext == ".txt" || ext == ".h5" || ext == ".hdf5" || ext == ".mat";
}

void writeLinearTransformFile(const AffineMatrix4& pointMap, const std::string& path)
{
  if (!isLinearTransformPath(path))
  {
    throwFileError(
      path, std::string("not an ITK transform file name (expected ") + extensionsText + ")");
  }
  if (!allFinite(pointMap))
  {
    throwFileError(path, "the transform to write has a value that is not finite");
  }
  if (pointMap[12] != 0.0 || pointMap[13] != 0.0 || pointMap[14] != 0.0 || pointMap[15] != 1.0)
  {
    throwFileError(path, "the transform to write is not affine (its last row is not 0 0 0 1)");
  }
  registerTransformIOs();
  using Affine = itk::AffineTransform<double, 3>;
  auto affine = Affine::New();
  Affine::MatrixType matrix;
  Affine::OutputVectorType translation;
  for (unsigned row = 0; row < 3; ++row)
  {
    for (unsigned column = 0; column < 3; ++column)
    {
      matrix(row, column) = pointMap[4 * row + column];
    }
    translation[row] = pointMap[4 * row + 3];
  }
  affine->SetMatrix(matrix);
  affine->SetTranslation(translation);

  auto writer = itk::TransformFileWriterTemplate<double>::New();
  writer->SetInput(affine);
  writer->SetFileName(path);
  try
  {
    writer->Update();
  }
  catch (const std::exception& e)
  {
    throwFileError(path, "cannot be written: " + detail::itkMessage(e));
  }
}

AffineMatrix4 readLinearTransformFile(const std::string& path)
{
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
  {
    throwFileError(path, std::filesystem::exists(path, error) ? "not a file" : "no such file");
  }
  if (!isLinearTransformPath(path))
  {
    throwFileError(
      path, std::string("not an ITK transform file name (expected ") + extensionsText + ")");
  }
  registerTransformIOs();
  auto reader = itk::TransformFileReaderTemplate<double>::New();
  reader->SetFileName(path);
  try
  {
    reader->Update();
  }
  catch (const std::exception& e)
  {
    throwFileError(path, "not a readable ITK transform file: " + detail::itkMessage(e));
  }
  const auto* transforms = reader->GetTransformList();
  if (transforms->empty())
  {
    throwFileError(path, "holds no transform");
  }
  // A composite is listed first, followed by its parts: it stands for all of them.
  const auto* first = transforms->front().GetPointer();
  const std::string className = first->GetNameOfClass();
  const bool composite = className.find("CompositeTransform") != std::string::npos;
  if (transforms->size() > 1 && !composite)
  {
    throwFileError(path,
      "holds " + std::to_string(transforms->size()) +
        " transforms; one linear transform is expected");
  }
  using Transform = itk::Transform<double, 3, 3>;
  const auto* transform = dynamic_cast<const Transform*>(first);
  if (!transform)
  {
    throwFileError(path, "holds a " + className + " that is not a 3-D transform");
  }
  if (transform->GetTransformCategory() != Transform::TransformCategoryEnum::Linear)
  {
    throwFileError(
      path, "holds a " + className + ", which is not linear; one linear transform is expected");
  }
  AffineMatrix4 pointMap{};
  pointMap[15] = 1.0;
  using MatrixOffset = itk::MatrixOffsetTransformBase<double, 3, 3>;
  if (const auto* matrixOffset = dynamic_cast<const MatrixOffset*>(transform))
  {
    // Exact: x -> M x + offset, the centre already folded into the offset.
    for (unsigned row = 0; row < 3; ++row)
    {
      for (unsigned column = 0; column < 3; ++column)
      {
        pointMap[4 * row + column] = matrixOffset->GetMatrix()(row, column);
      }
      pointMap[4 * row + 3] = matrixOffset->GetOffset()[row];
    }
    return finiteOrFail(pointMap, path);
  }
  // Any other linear map (a translation, a composite of linear transforms) is
  // fixed by the images of the origin and of the unit vectors.
  const Transform::InputPointType origin{};
  const Transform::OutputPointType originImage = transform->TransformPoint(origin);
  for (unsigned column = 0; column < 3; ++column)
  {
    Transform::InputPointType unit{};
    unit[column] = 1.0;
    const Transform::OutputPointType image = transform->TransformPoint(unit);
    for (unsigned row = 0; row < 3; ++row)
    {
      pointMap[4 * row + column] = image[row] - originImage[row];
    }
  }
  for (unsigned row = 0; row < 3; ++row)
  {
    pointMap[4 * row + 3] = originImage[row];
  }
  return finiteOrFail(pointMap, path);
}

} // namespace vimlop
