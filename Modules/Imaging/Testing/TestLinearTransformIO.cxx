#include <vimlop/Imaging/LinearTransformIO.h>

#include "ErrorMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace vimlop;
using vimlop::fixtures::errorMessageOf;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

std::string write(const std::string& name, const std::string& text)
{
  const std::string path = out + "/" + name;
  std::ofstream(path) << text;
  return path;
}

/// A similarity with every entry different: 1.7 times a rotation of 0.9 rad
/// about (1, 2, 3), then a translation of some decimetres.
AffineMatrix4 scaledRotationAndTranslation()
{
  const double angle = 0.9;
  double axis[3] = { 1.0, 2.0, 3.0 };
  const double norm = std::sqrt(14.0);
  for (double& a : axis)
  {
    a /= norm;
  }
  const double c = std::cos(angle), s = std::sin(angle), C = 1.0 - c;
  const double x = axis[0], y = axis[1], z = axis[2], scale = 1.7;
  return { scale * (c + x * x * C), scale * (x * y * C - z * s), scale * (x * z * C + y * s),
    -123.456, scale * (y * x * C + z * s), scale * (c + y * y * C), scale * (y * z * C - x * s),
    78.9012345, scale * (z * x * C - y * s), scale * (z * y * C + x * s), scale * (c + z * z * C),
    301.0000001, 0.0, 0.0, 0.0, 1.0 };
}

void expectSameMatrix(const AffineMatrix4& expected, const AffineMatrix4& actual, double tolerance)
{
  for (int i = 0; i < 16; ++i)
  {
    EXPECT_NEAR(expected[i], actual[i], tolerance) << "entry " << i / 4 << "," << i % 4;
  }
}

} // namespace

TEST(LinearTransformIO, WritesAndReadsBackAScaledRotationExactlyInEveryFormat)
{
  const AffineMatrix4 pointMap = scaledRotationAndTranslation();
  for (const std::string name : { "similarity.tfm", "similarity.h5", "similarity.mat" })
  {
    SCOPED_TRACE(name);
    writeLinearTransformFile(pointMap, out + "/" + name);
    expectSameMatrix(pointMap, readLinearTransformFile(out + "/" + name), 1e-13);
  }
}

TEST(LinearTransformIO, WritesTheTextFormItkAndSlicerRead)
{
  writeLinearTransformFile(scaledRotationAndTranslation(), out + "/text-form.tfm");
  std::ifstream file(out + "/text-form.tfm");
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_NE(text.str().find("#Insight Transform File V1.0"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("Transform: AffineTransform_double_3_3"), std::string::npos);
  EXPECT_NE(text.str().find("FixedParameters: 0 0 0"), std::string::npos);
}

TEST(LinearTransformIO, FoldsTheCentreOfARigidTransformIntoItsTranslation)
{
  // An Euler3DTransform written by another program: a quarter turn about z
  // around the centre (10, 0, 0), no translation; the point (10, 0, 0) stays.
  const std::string path = write("euler-centre.tfm",
    "#Insight Transform File V1.0\n#Transform 0\nTransform: Euler3DTransform_double_3_3\n"
    "Parameters: 0 0 1.5707963267948966 0 0 0\nFixedParameters: 10 0 0 0\n");
  const AffineMatrix4 pointMap = readLinearTransformFile(path);
  const AffineMatrix4 expected = { 0, -1, 0, 10, 1, 0, 0, -10, 0, 0, 1, 0, 0, 0, 0, 1 };
  expectSameMatrix(expected, pointMap, 1e-12);
}

TEST(LinearTransformIO, ReadsATranslationThatHasNoMatrix)
{
  const std::string path = write("translation.tfm",
    "#Insight Transform File V1.0\n#Transform 0\nTransform: TranslationTransform_double_3_3\n"
    "Parameters: 1.5 -2 30\nFixedParameters: \n");
  const AffineMatrix4 expected = { 1, 0, 0, 1.5, 0, 1, 0, -2, 0, 0, 1, 30, 0, 0, 0, 1 };
  expectSameMatrix(expected, readLinearTransformFile(path), 1e-15);
}

TEST(LinearTransformIO, RefusesFilesThatDoNotHoldOneLinearTransform)
{
  EXPECT_EQ(errorMessageOf([] { readLinearTransformFile(out + "/absent.tfm"); }),
    "'" + out + "/absent.tfm': no such file");
  const std::string wrongName = write("pose.json", "{}");
  EXPECT_EQ(errorMessageOf([&] { readLinearTransformFile(wrongName); }),
    "'" + wrongName +
      "': not an ITK transform file name (expected .tfm, .txt, .h5, .hdf5 or .mat)");

  const std::string garbage = write("garbage.tfm", "this is not a transform\n");
  EXPECT_EQ(errorMessageOf([&] { readLinearTransformFile(garbage); })
              .rfind("'" + garbage + "': not a readable ITK transform file: ", 0),
    0u);

  const std::string two = write("two.tfm",
    "#Insight Transform File V1.0\n#Transform 0\nTransform: TranslationTransform_double_3_3\n"
    "Parameters: 1 2 3\nFixedParameters: \n#Transform 1\n"
    "Transform: TranslationTransform_double_3_3\nParameters: 1 2 3\nFixedParameters: \n");
  EXPECT_EQ(errorMessageOf([&] { readLinearTransformFile(two); }),
    "'" + two + "': holds 2 transforms; one linear transform is expected");

  // A B-spline on a 4 x 4 x 4 grid of control points, all at rest.
  std::string bspline = "#Insight Transform File V1.0\n#Transform 0\n"
                        "Transform: BSplineTransform_double_3_3\nParameters:";
  for (int i = 0; i < 3 * 64; ++i)
  {
    bspline += " 0";
  }
  bspline += "\nFixedParameters: 4 4 4 0 0 0 1 1 1 1 0 0 0 1 0 0 0 1\n";
  const std::string nonlinear = write("bspline.tfm", bspline);
  EXPECT_EQ(errorMessageOf([&] { readLinearTransformFile(nonlinear); }),
    "'" + nonlinear +
      "': holds a BSplineTransform, which is not linear; one linear transform is expected");
}

TEST(LinearTransformIO, RefusesToWriteWhatIsNotAnAffineTransformFile)
{
  AffineMatrix4 pointMap = scaledRotationAndTranslation();
  EXPECT_EQ(errorMessageOf([&] { writeLinearTransformFile(pointMap, out + "/pose.json"); }),
    "'" + out +
      "/pose.json': not an ITK transform file name (expected .tfm, .txt, .h5, .hdf5 or .mat)");
  pointMap[14] = 0.5;
  EXPECT_EQ(errorMessageOf([&] { writeLinearTransformFile(pointMap, out + "/projective.tfm"); }),
    "'" + out +
      "/projective.tfm': the transform to write is not affine (its last row is not 0 0 0 1)");
  pointMap = scaledRotationAndTranslation();
  pointMap[3] = std::nan("");
  EXPECT_EQ(errorMessageOf([&] { writeLinearTransformFile(pointMap, out + "/nan.tfm"); }),
    "'" + out + "/nan.tfm': the transform to write has a value that is not finite");
  EXPECT_EQ(
    errorMessageOf(
      [&] { writeLinearTransformFile(scaledRotationAndTranslation(), out + "/no-folder/x.tfm"); })
      .rfind("'" + out + "/no-folder/x.tfm': cannot be written: ", 0),
    0u);
}
