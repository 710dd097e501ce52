#ifndef vimlop_FieldOfView_h
#define vimlop_FieldOfView_h

#include <vimlop/Video/FieldOfViewOptions.h>

#include <opencv2/core/mat.hpp>

#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief The part of an endoscope's frames that shows anatomy: inside the
 * field stop (the black disc border of every real frame), shrunk by a
 * margin. Contour points and SfM features outside it are not used: the
 * field stop's edge is a strong step whose dark side stays dark, which the
 * contour detector would otherwise take for an occluding contour.
 *
 * A small value: a CV_8U mask (255 valid, 0 not, the frames' size) and,
 * when the field of view is a circle, its centre and radius (before the
 * margin).
 */
class FieldOfView
{
public:
  /// @brief Every pixel valid (no field stop) for frames of this size.
  static FieldOfView everything(int widthPx, int heightPx);
  /**
   * @brief The disc of this centre and radius, pixels, shrunk by `marginPx`.
   * @throws vimlop::Error for a non-positive size or radius, or a negative margin.
   */
  static FieldOfView circle(int widthPx, int heightPx, double centreUPx, double centreVPx,
    double radiusPx, double marginPx);
  /**
   * @brief The white (non-zero) part of a mask image file, eroded by `marginPx`.
   * @throws vimlop::Error when the file cannot be read, its size is not the
   * frames' or it has no white pixel.
   */
  static FieldOfView fromFile(const std::string& path, int widthPx, int heightPx, double marginPx);
  /**
   * @brief Detects the field stop of a sequence of 8-bit frames: the per-pixel
   * maximum over the frames (median-filtered), thresholded, its largest bright
   * connected region, filled, eroded by the margin. A border smaller than
   * `autoMinBorderFraction` of the frame gives everything().
   * @throws vimlop::Error for no frames, frames of different sizes or not 8-bit.
   */
  static FieldOfView detect(const std::vector<cv::Mat>& frames, const FieldOfViewOptions& options);
  /**
   * @brief The field of view `options` ask for, for these frames (None
   * gives everything(), Auto detect()).
   * @throws vimlop::Error as the factories above.
   */
  static FieldOfView ofSequence(
    const std::vector<cv::Mat>& frames, const FieldOfViewOptions& options);

  /// @brief The mask: CV_8U, 255 where contours and features are used.
  const cv::Mat& mask() const { return this->Mask; }
  /// @brief True when every pixel is valid (then nothing is masked at all).
  bool isEverything() const { return this->Everything; }
  /// @brief True when the field stop is a circle (given, or a detected border close to one).
  bool isCircular() const { return this->Circular; }
  /// @brief The circle's centre, pixels (0 when not circular).
  double centreUPx() const { return this->CentreUPx; }
  double centreVPx() const { return this->CentreVPx; }
  /// @brief The circle's radius before the margin, pixels (0 when not circular).
  double radiusPx() const { return this->RadiusPx; }
  /// @brief The fraction of the frame's pixels that are valid.
  double validFraction() const;
  /// @brief True when the pixel nearest (u, v) is valid (false outside the frame).
  bool contains(double uPx, double vPx) const;

private:
  cv::Mat Mask;
  bool Everything = true;
  bool Circular = false;
  double CentreUPx = 0.0;
  double CentreVPx = 0.0;
  double RadiusPx = 0.0;
};

} // namespace vimlop

#endif
