#ifndef vimlop_FieldStop_h
#define vimlop_FieldStop_h

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

namespace vimlop
{

/**
 * @brief The endoscope's image circle: the field stop of its relay optics,
 * seen as a black disc border on every real frame, and the darkening of the
 * picture towards it (vignetting and the fall-off of the light guide).
 *
 * Off by default (no circle, no vignetting), the ideal world of P1–P3.
 * Realistic values and their sources: Documentation/Simulation.md.
 */
struct FieldStopOptions
{
  /// Radius of the circle as a fraction of the image's half-diagonal (default
  /// 0: none). A rigid sinus endoscope's circle is about as tall as the
  /// sensor: 0.6 for 4:3 frames (Documentation/Simulation.md). Give this or
  /// radiusPx, not both.
  double radiusFraction = 0.0;
  /// Radius of the circle, pixels (default 0: none; see radiusFraction).
  double radiusPx = 0.0;
  /// Centre of the circle relative to the image centre ((width - 1) / 2,
  /// (height - 1) / 2), pixels, u right and v down (default (0, 0)). Real
  /// scopes sit a few pixels off centre on the sensor (an estimate).
  Eigen::Vector2d centreOffsetPx = Eigen::Vector2d::Zero();
  /// Width of the circle's edge, pixels: the gain falls linearly from 1 to 0
  /// over this width centred on the radius (default 1.5: the field stop is
  /// imaged slightly out of focus; an estimate; 0 for a hard step).
  double edgeSoftnessPx = 1.5;
  /// Vignetting: the fraction of brightness lost at the circle's edge
  /// relative to its centre, with the gain 1 - strength * (r / R)^2 (the
  /// first-order term of cos^4 fall-off; R is the circle's radius, or the
  /// half-diagonal without a circle). Default 0: none; in [0, 1].
  double vignettingStrength = 0.0;

  /// @brief True when the options change no pixel (no circle, no vignetting).
  bool isOff() const
  {
    return radiusFraction == 0.0 && radiusPx == 0.0 && vignettingStrength == 0.0;
  }

  /// @brief The circle's radius for an image of this size, pixels (0 when there is none).
  double radiusFor(int widthPx, int heightPx) const;

  /**
   * @brief Checks the settings.
   * @throws vimlop::Error naming the first problem (a negative or non-finite
   * value, both radii given, a vignetting strength outside [0, 1]).
   */
  void validate() const;
};

/**
 * @brief The per-pixel gain of the field stop and vignetting for an image of
 * this size: 1 at the centre without vignetting, 0 outside the circle (a
 * single-channel CV_32F image). Multiply a frame by it before the sensor
 * noise: a real sensor is noisy in the black border too.
 */
cv::Mat fieldStopGain(const FieldStopOptions& options, int widthPx, int heightPx);

} // namespace vimlop

#endif
