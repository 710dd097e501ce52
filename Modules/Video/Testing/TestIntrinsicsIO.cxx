#include <vimlop/Core/Error.h>
#include <vimlop/Video/IntrinsicsIO.h>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

using namespace vimlop;

namespace
{

const std::string out = VIMLOP_TEST_OUTPUT_DIR;

PinholeCamera makeCamera()
{
  PinholeCamera k;
  k.fx = 412.5;
  k.fy = 410.25;
  k.cx = 319.75;
  k.cy = 241.5;
  k.widthPx = 640;
  k.heightPx = 480;
  k.distortion.resize(5);
  k.distortion << -0.3, 0.1, 0.001, -0.002, 0.0;
  return k;
}

std::string messageOf(const std::string& path)
{
  try
  {
    readIntrinsics(path);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace

class IntrinsicsRoundTrip : public ::testing::TestWithParam<std::string>
{
};

TEST_P(IntrinsicsRoundTrip, KeepsEveryValue)
{
  const PinholeCamera k = makeCamera();
  const std::string path = out + "/intrinsics" + GetParam();
  writeIntrinsics(k, path);
  const PinholeCamera back = readIntrinsics(path);
  EXPECT_EQ(back.fx, k.fx);
  EXPECT_EQ(back.fy, k.fy);
  EXPECT_EQ(back.cx, k.cx);
  EXPECT_EQ(back.cy, k.cy);
  EXPECT_EQ(back.widthPx, 640);
  EXPECT_EQ(back.heightPx, 480);
  ASSERT_EQ(back.distortion.size(), 5);
  EXPECT_EQ(back.distortion, k.distortion);
  EXPECT_EQ(back.lensModel, LensModel::RadialTangential);
}

TEST_P(IntrinsicsRoundTrip, KeepsAFisheyeLensAndItsFourCoefficients)
{
  PinholeCamera k = makeCamera();
  k.lensModel = LensModel::Fisheye;
  k.distortion = Eigen::Vector4d(0.03, -0.01, 0.002, -0.0005);
  const std::string path = out + "/fisheye-intrinsics" + GetParam();
  writeIntrinsics(k, path);
  const PinholeCamera back = readIntrinsics(path);
  EXPECT_EQ(back.lensModel, LensModel::Fisheye);
  EXPECT_EQ(back.distortion, k.distortion);
  EXPECT_EQ(back.fx, k.fx);
  // The default model is not named, so that such files stay as they were.
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("fisheye"), std::string::npos);
  writeIntrinsics(makeCamera(), path);
  std::ifstream again(path);
  const std::string plain(
    (std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
  EXPECT_EQ(plain.find("distortion_model"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Formats, IntrinsicsRoundTrip, ::testing::Values(".yaml", ".json", ".xml"),
  [](const auto& info) { return info.param.substr(1); });

TEST(IntrinsicsIO, ReadsPlainNumbers)
{
  const std::string path = out + "/plain.json";
  std::ofstream(path)
    << R"({"fx": 500, "fy": 501.5, "cx": 320, "cy": 240, "width": 640, "height": 480})";
  const PinholeCamera k = readIntrinsics(path);
  EXPECT_EQ(k.fy, 501.5);
  EXPECT_EQ(k.widthPx, 640);
  EXPECT_EQ(k.distortion.size(), 0);
}

TEST(IntrinsicsIO, ReadsTheLensModelByOpenCVsAndROSsNames)
{
  const std::string path = out + "/equidistant.json";
  std::ofstream(path) << R"({"fx": 500, "fy": 500, "cx": 320, "cy": 240, "width": 640, )"
                      << R"("height": 480, "distortion_model": "equidistant", )"
                      << R"("distortion": [0.1, 0.01, 0, 0]})";
  EXPECT_EQ(readIntrinsics(path).lensModel, LensModel::Fisheye);
  const std::string plumbBob = out + "/plumb-bob.yaml";
  std::ofstream(plumbBob) << "%YAML:1.0\n---\nfx: 500\nfy: 500\ncx: 320\ncy: 240\nwidth: 640\n"
                             "height: 480\ndistortion_model: plumb_bob\n"
                             "distortion: [ -0.3, 0.1, 0, 0, 0.01 ]\n";
  const PinholeCamera k = readIntrinsics(plumbBob);
  EXPECT_EQ(k.lensModel, LensModel::RadialTangential);
  EXPECT_EQ(k.distortion.size(), 5);
}

TEST(IntrinsicsIO, RefusesAnUnknownLensModelAndAFisheyeWithoutFourCoefficients)
{
  const std::string unknown = out + "/unknown-model.yaml";
  std::ofstream(unknown)
    << "%YAML:1.0\n---\nfx: 500\nfy: 500\ncx: 320\ncy: 240\nwidth: 640\n"
       "height: 480\ndistortion_model: kannala\ndistortion: [ 0.1, 0, 0, 0 ]\n";
  EXPECT_EQ(messageOf(unknown),
    "'" + unknown +
      "': unknown distortion_model 'kannala' (expected plumb_bob or radial_tangential, OpenCV's "
      "default, or fisheye or equidistant)");
  const std::string five = out + "/fisheye-five.yaml";
  std::ofstream(five) << "%YAML:1.0\n---\nfx: 500\nfy: 500\ncx: 320\ncy: 240\nwidth: 640\n"
                         "height: 480\ndistortion_model: fisheye\n"
                         "distortion: [ 0.1, 0, 0, 0, 0 ]\n";
  EXPECT_EQ(messageOf(five),
    "'" + five +
      "': the fisheye lens model needs exactly 4 distortion coefficients (k1, k2, k3, k4), not 5");
  PinholeCamera k = makeCamera();
  k.lensModel = LensModel::Fisheye;
  try
  {
    writeIntrinsics(k, out + "/fisheye-five-written.yaml");
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_EQ(std::string(e.what()),
      "'" + out +
        "/fisheye-five-written.yaml': refusing to write invalid intrinsics: the fisheye lens "
        "model needs exactly 4 distortion coefficients (k1, k2, k3, k4), not 5");
  }
}

TEST(IntrinsicsIO, ErrorsNameTheFileAndTheProblem)
{
  EXPECT_EQ(messageOf(out + "/none.yaml"), "'" + out + "/none.yaml': no such file");
  const std::string missing = out + "/missing-fy.json";
  std::ofstream(missing) << R"({"fx": 500, "cx": 320, "cy": 240, "width": 640, "height": 480})";
  EXPECT_EQ(messageOf(missing), "'" + missing + "': missing or non-numeric entry 'fy'");
  const std::string negative = out + "/negative.json";
  std::ofstream(negative)
    << R"({"fx": -5, "fy": 5, "cx": 320, "cy": 240, "width": 640, "height": 480})";
  EXPECT_EQ(
    messageOf(negative), "'" + negative + "': focal lengths must be positive (fx=-5, fy=5)");
  const std::string malformed = out + "/malformed.yaml";
  std::ofstream(malformed) << "%YAML:1.0\n---\nfx: [1, 2\n";
  EXPECT_EQ(messageOf(malformed).rfind("'" + malformed + "': ", 0), 0u) << messageOf(malformed);
  // Found by fuzzing: a declared size is checked before OpenCV allocates it.
  const std::string huge = out + "/huge.yaml";
  std::ofstream(huge)
    << "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n"
       "camera_matrix: !!opencv-matrix\n   rows: 100000\n   cols: 100000\n   dt: d\n"
       "   data: [ 1. ]\n";
  EXPECT_EQ(messageOf(huge), "'" + huge + "': 'camera_matrix' has an invalid size 100000x100000");
  const std::string text = out + "/intrinsics.txt";
  std::ofstream(text) << "fx 500";
  EXPECT_EQ(messageOf(text),
    "'" + text + "': unsupported intrinsics file type (expected .yaml, .yml, .json or .xml)");
}
