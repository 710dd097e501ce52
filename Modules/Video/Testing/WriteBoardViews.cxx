// Writes the calibration tests' rendered chessboard views as PNG files, for
// the tests of `vimlop calibrate`: view00.png ... into the folder given, through
// the barrel lens or, with "fisheye", the fisheye lens of BoardViews.h.

#include "BoardViews.h"

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <string>

int main(int argc, char** argv)
{
  if (argc != 3 || (std::string(argv[2]) != "barrel" && std::string(argv[2]) != "fisheye"))
  {
    std::fprintf(stderr, "usage: %s FOLDER barrel|fisheye\n", argv[0]);
    return 2;
  }
  using namespace vimlop;
  const PinholeCamera lens = fixtures::trueCamera(
    std::string(argv[2]) == "fisheye" ? LensModel::Fisheye : LensModel::RadialTangential);
  std::filesystem::create_directories(argv[1]);
  const std::vector<cv::Mat> views = fixtures::boardViews(lens);
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
  std::printf("wrote %zu views of a 9x6 board (5 mm squares) through a %s lens: fx %g fy %g cx "
              "%g cy %g\n",
    views.size(), argv[2], lens.fx, lens.fy, lens.cx, lens.cy);
  return 0;
}
