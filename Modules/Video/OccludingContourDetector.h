#ifndef vimlop_OccludingContourDetector_h
#define vimlop_OccludingContourDetector_h

#include <vimlop/Core/ContourPoint.h>
#include <vimlop/Video/ContourDetectionOptions.h>

#include <opencv2/core/mat.hpp>

#include <cstddef>
#include <vector>

namespace vimlop
{

/**
 * @brief Finds occluding contours in an endoscopic frame, with their normals
 * (DESIGN §4, V1).
 *
 * With the light at the endoscope, the surface behind an occluding contour is
 * farther from the light than the surface in front of it, so it is darker by
 * the inverse-square fall-off: an occluding contour is a sharp step in the
 * logarithm of the intensity whose dark side stays dark well away from it.
 * The detector works on the log intensity (a ratio of intensities is then
 * the same step in bright and dark regions) of the red channel by default
 * (see ContourChannel), smooths it with a Gaussian (`smoothingSigmaPx`),
 * takes its gradient, thins the edges by non-maximum suppression along the
 * gradient and keeps the ones connected to a strong edge (hysteresis).
 * Texture and shading edges are then suppressed twice:
 * - by scale (`minScaleRatio`): a step keeps getting weaker as the smoothing
 *   grows, the mucosa's gradual shading and colour changes do not;
 * - by the dark-side test (`darkSideProbesPx`, `darkSideMinLogStep`): at
 *   every probe distance along the normal the far side must be darker than
 *   the near side (a vessel is dark only across its width, a contour's far
 *   side is dark all the way).
 * Chains shorter than `minChainLengthPx` are dropped. Each remaining edge
 * pixel is placed with sub-pixel accuracy along the gradient, gets the unit
 * negative gradient of the smoothed frame as its normal (pointing from the
 * near, brighter side to the far, darker side), and the points are thinned to
 * about one per `spacingPx`.
 */
class OccludingContourDetector
{
public:
  OccludingContourDetector();
  explicit OccludingContourDetector(const ContourDetectionOptions& options);

  const ContourDetectionOptions& options() const { return this->Opts; }

  /**
   * @brief The oriented contour points of an 8-bit BGR (or grey) frame.
   * @throws vimlop::Error for an empty frame or an unsupported pixel type.
   */
  std::vector<ContourPoint> detect(const cv::Mat& frame) const;

  /// @brief How many points a masked detection removed.
  struct MaskedDetectionCounts
  {
    /// The points detect(frame) would return (without the mask).
    size_t detected = 0;
    /// Those of them on an invalid pixel of the mask.
    size_t dropped = 0;
  };

  /**
   * @brief The oriented contour points of a frame that lie on valid
   * (non-zero) pixels of `validMask` (a CV_8U image of the frame's size,
   * e.g. FieldOfView::mask(); empty: every pixel valid, as detect(frame)).
   * Points are masked before they are thinned, so none on the field stop's
   * edge pushes out a real contour point. `counts`, when given, receives
   * what the mask removed.
   * @throws vimlop::Error as detect(frame), or for a mask of another size or type.
   */
  std::vector<ContourPoint> detect(
    const cv::Mat& frame, const cv::Mat& validMask, MaskedDetectionCounts* counts = nullptr) const;

  /**
   * @brief Keeps points, in the given order, that lie at least `spacingPx`
   * from every point kept before them (detect() orders its points by edge
   * strength, so the best-localised ones are kept).
   */
  static std::vector<ContourPoint> thin(const std::vector<ContourPoint>& points, double spacingPx);

private:
  /// Every edge point that passes the tests, strongest first, not thinned.
  std::vector<ContourPoint> edgePoints(const cv::Mat& frame) const;

  ContourDetectionOptions Opts;
};

} // namespace vimlop

#endif
