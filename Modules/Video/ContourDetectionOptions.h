#ifndef vimlop_ContourDetectionOptions_h
#define vimlop_ContourDetectionOptions_h

#include <vector>

/**
 * @file ContourDetectionOptions.h
 * @brief The settings of the video contour detector, apart from the detector
 * (and OpenCV), so that option structs holding them stay light.
 */
namespace vimlop
{

/// @brief The image channel the contour detector works on.
enum class ContourChannel
{
  /// Luminance (0.299 R + 0.587 G + 0.114 B).
  Luminance,
  /// Red only: haemoglobin absorbs green and blue far more than red, so
  /// vessels and most mucosal texture are faint in red while the light's
  /// fall-off with distance, which makes occluding contours, is not.
  Red
};

/// @brief Parameters of OccludingContourDetector; pixels, and natural-log units of intensity.
struct ContourDetectionOptions
{
  /// The channel (default red).
  ContourChannel channel = ContourChannel::Red;
  /// Added to 8-bit intensities before the logarithm, grey levels (default
  /// 8), so sensor noise in dark regions does not become large steps.
  double logOffset = 8.0;
  /// Gaussian smoothing before the gradient, pixels (default 1.2).
  double smoothingSigmaPx = 1.2;
  /// Hysteresis thresholds on the log-intensity gradient, per pixel (defaults 0.04 and 0.02).
  double highThreshold = 0.04;
  double lowThreshold = 0.02;
  /// Scale test: least ratio of the gradient at smoothingSigmaPx to the
  /// strongest gradient nearby at twice that smoothing (default 1.2; 0
  /// disables the test). Smoothing halves the gradient of a step, such as
  /// a depth discontinuity, whenever it doubles, but hardly weakens the
  /// gradual shading and colour changes of the mucosa, which are wider
  /// than the smoothing.
  double minScaleRatio = 1.2;
  /// Distances along the normal at which the dark side is probed, pixels (default 3 and 7).
  std::vector<double> darkSideProbesPx = { 3.0, 7.0 };
  /// Least log-intensity drop from near to far side at every probe (default 0.08: 8 % darker).
  double darkSideMinLogStep = 0.08;
  /// Chains of edge pixels shorter than this are dropped, pixels (default 12).
  int minChainLengthPx = 12;
  /// Edge pixels this close to the image border are dropped, pixels (default 4).
  int borderPx = 4;
  /// Least distance between returned points, pixels (default 3; 0 returns
  /// every edge pixel, strongest first).
  double spacingPx = 3.0;
};
} // namespace vimlop

#endif
