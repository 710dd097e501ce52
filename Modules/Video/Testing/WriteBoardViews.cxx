// Writes the calibration tests' rendered board views as PNG files, for the
// tests of `vimlop calibrate`: view00.png ... into the folder given, through
// the barrel lens or, with "fisheye", the fisheye lens of BoardViews.h; of
// the chessboard or, with "charuco", the ChArUco board, moved over the image
// as boardViews() does with the spread given (default 1).

#include "BoardViews.h"

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

int main(int argc, char** argv)
{
  const std::string pattern = argc > 3 ? argv[3] : "chessboard";
  const double spread = argc > 4 ? std::atof(argv[4]) : 1.0;
  if (argc < 3 || argc > 5 ||
    (std::string(argv[2]) != "barrel" && std::string(argv[2]) != "fisheye") ||
    (pattern != "chessboard" && pattern != "charuco") || !(spread > 0.0))
  {
    std::fprintf(
      stderr, "usage: %s FOLDER barrel|fisheye [chessboard|charuco [SPREAD]]\n", argv[0]);
    return 2;
  }
  using namespace vimlop;
  const PinholeCamera lens = fixtures::trueCamera(
    std::string(argv[2]) == "fisheye" ? LensModel::Fisheye : LensModel::RadialTangential);
  std::filesystem::create_directories(argv[1]);
  const std::vector<cv::Mat> views = fixtures::boardViews(lens,
    pattern == "charuco" ? fixtures::charucoBoard()
                         : fixtures::BoardPattern(fixtures::chessboardAt),
    spread);
  for (size_t v = 0; v < views.size(); ++v)
  {
    char name[32];
    std::snprintf(name, sizeof name, "view%02zu.png", v);
    if (!cv::imwrite((std::filesystem::path(argv[1]) / name).string(), views[v]))
    {
      std::fprintf(stderr, "cannot write %s\n", name);
      return 1;
    }
  }
  std::printf("wrote %zu views of a 9x6 %s (inner corners, 5 mm squares) through a %s lens: fx %g "
              "fy %g cx %g cy %g\n",
    views.size(), pattern.c_str(), argv[2], lens.fx, lens.fy, lens.cx, lens.cy);
  return 0;
}
