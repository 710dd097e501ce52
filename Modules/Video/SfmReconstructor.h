#ifndef vimlop_SfmReconstructor_h
#define vimlop_SfmReconstructor_h

// Private to the Video module (not installed).

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Video/SfmReconstruction.h>
#include <vimlop/Video/StructureFromMotion.h>

#include <Eigen/Core>

#include <opencv2/core.hpp>

#include <iosfwd>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vimlop::detail
{

/**
 * @brief One incremental reconstruction of StructureFromMotion::reconstruct,
 * on frames and intrinsics it has checked.
 *
 * The stages share the state below; each is defined in a source of its own:
 * features, matches and tracks in SfmReconstructorTracks.cxx, the initial
 * pair in SfmReconstructorInitialPair.cxx, new points in
 * SfmReconstructorTriangulation.cxx, new frames in
 * SfmReconstructorRegistration.cxx, and the run, bundle adjustment and
 * result in SfmReconstructor.cxx.
 */
class SfmReconstructor
{
public:
  SfmReconstructor(const StructureFromMotionOptions& options, const std::vector<cv::Mat>& frames,
    const PinholeCamera& k, std::ostream* log, const cv::Mat& featureMask);

  SfmReconstruction run(const std::vector<std::string>& names);

private:
  struct FrameFeatures
  {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
  };

  struct PairMatches
  {
    int first = 0;
    int second = 0;
    std::vector<std::pair<int, int>> matches; ///< keypoint indices, verified
    cv::Mat essential;
  };

  /// One feature track: a keypoint per frame, and the point it became.
  struct Track
  {
    std::vector<std::pair<int, int>> features; ///< (frame, keypoint)
    int point = -1;
  };

  void say(const std::string& text);

  void detect();
  void match();
  void buildTracks();

  void initialise();

  Eigen::Vector2d normalised(const Eigen::Vector2d& pixel) const;
  /// Points for tracks seen by at least two registered frames.
  void triangulateTracks();

  /// Observations of existing points in a newly registered frame, if they agree.
  void addObservations(int frame);
  void registerRemaining();

  void adjust(int iterations);
  SfmReconstruction result(const std::vector<std::string>& names);

  const StructureFromMotionOptions& O;
  const std::vector<cv::Mat>& Frames;
  /// Where features are detected (empty: everywhere).
  cv::Mat FeatureMask;
  PinholeCamera K;
  std::ostream* Log;
  std::vector<FrameFeatures> Features;
  std::vector<PairMatches> Pairs;
  std::vector<Track> Tracks;
  std::vector<std::map<int, int>> TrackOf; ///< per frame: keypoint -> track
  std::vector<bool> Registered;
  std::vector<CameraPose> Poses;
  int StaticPairs = 0;
  double LargestMotionPx = 0.0;
  int Origin = 0;
  int ScaleCamera = 0;
  std::vector<Eigen::Vector3d> Points;
  std::vector<std::vector<std::pair<int, Eigen::Vector2d>>> Observations;
};

} // namespace vimlop::detail

#endif
