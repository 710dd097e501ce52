#ifndef vimlop_StructureFromMotion_h
#define vimlop_StructureFromMotion_h

#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Video/SfmReconstruction.h>

#include <opencv2/core/mat.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief The image channel features are found in.
enum class StructureFromMotionChannel
{
  /// Luminance (OpenCV's BGR to grey).
  Luminance,
  /// Green: the blood-borne texture of mucosa (vessels, mottling) has its
  /// highest contrast there, since haemoglobin absorbs green most.
  Green
};

/// @brief Parameters; pixels and degrees.
struct StructureFromMotionOptions
{
  /// Channel of the SIFT features (default green).
  StructureFromMotionChannel channel = StructureFromMotionChannel::Green;
  /// SIFT: at most this many features per frame (default 4000; 0: all).
  int maxFeatures = 4000;
  /// SIFT contrast threshold (default 0.005; OpenCV's 0.04 finds a few
  /// dozen features on low-contrast mucosa).
  double contrastThreshold = 0.005;
  /// Frames with fewer features than this are left out (default 40).
  int minFeatures = 40;
  /// Each frame is matched with the next `matchWindow` frames (default 5).
  int matchWindow = 5;
  /// Lowe's ratio test (default 0.8).
  double ratio = 0.8;
  /// RANSAC threshold of the essential matrix and of PnP, pixels (defaults 1 and 2).
  double essentialThresholdPx = 1.0;
  double pnpThresholdPx = 2.0;
  /// Least verified matches of a pair of frames (default 30).
  int minPairMatches = 30;
  /// Pairs whose matches move less than this (median) are not used: no
  /// epipolar geometry, pixels (default 0.5).
  double minMotionPx = 0.5;
  /// Least median triangulation angle of the initial pair, degrees (default 2).
  double minInitialAngleDeg = 2.0;
  /// Least ray angle for a new point, degrees (default 1.5).
  double minTriangulationAngleDeg = 1.5;
  /// Least 2-D to 3-D correspondences (PnP inliers) to register a frame (default 20).
  int minRegistrationPoints = 20;
  /// Observations with a larger reprojection error are removed, pixels (default 2.5).
  double maxReprojectionErrorPx = 2.5;
  /// Points seen in fewer frames are removed at the end (default 3).
  int minTrackLength = 3;
  /// Threads of feature detection and matching, the caller included (default
  /// 0: the hardware concurrency). The reconstruction does not depend on it.
  int threads = 0;
};

/**
 * @brief Incremental structure from motion for short endoscopic sequences
 * (about 30 frames).
 *
 * 1. SIFT features (OpenCV) in every frame.
 * 2. Matching of every frame with the next `matchWindow` frames (nearest
 *    neighbour with Lowe's ratio test, both ways), verified by an essential
 *    matrix found with RANSAC; matches are chained into tracks.
 * 3. Initialisation from the pair of frames with the most matches whose
 *    median triangulation angle reaches `minInitialAngleDeg`: relative pose
 *    from the essential matrix, triangulation, bundle adjustment.
 * 4. Incremental registration: the frame that sees the most reconstructed
 *    points next, by PnP with RANSAC and refinement; tracks seen by two
 *    registered frames with enough ray angle are triangulated; bundle
 *    adjustment (BundleAdjustment, a sparse Levenberg-Marquardt) after every
 *    frame; observations with large errors are removed.
 * 5. A final adjustment; the SfM frame is the first camera of the initial
 *    pair, scaled so that consecutive registered cameras are one unit apart
 *    on average; per-point covariances from the triangulation geometry with
 *    the final RMS reprojection error as image noise.
 */
class StructureFromMotion
{
public:
  StructureFromMotion();
  explicit StructureFromMotion(const StructureFromMotionOptions& options);

  const StructureFromMotionOptions& options() const { return this->Opts; }

  /**
   * @brief Reconstructs `frames` (8-bit BGR or grey, one size) taken with
   * `intrinsics` (undistorted). `names` name the frames (default
   * "frame<i>"). Progress and what was dropped go to `log` when given.
   *
   * @throws vimlop::Error for fewer than 2 frames, frames of different sizes,
   * intrinsics that do not match the frame size, or when SfM cannot
   * initialise: frames without texture (too few features or matches) or a
   * camera that does not move (no pair of frames with enough parallax).
   */
  SfmReconstruction reconstruct(const std::vector<cv::Mat>& frames, const PinholeCamera& intrinsics,
    const std::vector<std::string>& names = std::vector<std::string>(),
    std::ostream* log = nullptr) const;

  /**
   * @brief Features are detected only on the non-zero pixels of this CV_8U
   * mask of the frames' size (e.g. FieldOfView::mask()); empty (the
   * default): everywhere.
   */
  void setFeatureMask(const cv::Mat& mask) { this->FeatureMask = mask; }
  const cv::Mat& featureMask() const { return this->FeatureMask; }

private:
  StructureFromMotionOptions Opts;
  cv::Mat FeatureMask;
};

} // namespace vimlop

#endif
