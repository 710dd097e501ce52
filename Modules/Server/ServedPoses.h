#ifndef vimlop_ServedPoses_h
#define vimlop_ServedPoses_h

#include <vimlop/Core/FramePose.h>
#include <vimlop/Core/SimilarityTransform.h>

#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief A registration's own judgement of its result (V13), told to
/// clients as an OpenIGTLink STATUS message after the poses.
struct PoseVerdict
{
  /// True when the registration flagged its result as a failure: do not navigate with it.
  bool flagged = false;
  /// For people, e.g. "contour error 2.1 px, within the threshold 6 px" or
  /// why the result is flagged.
  std::string text;
};

/// @brief A frame of the video that has no pose: the scope was not tracked there.
struct FrameWithoutPose
{
  int frameId = 0;
  /// Its time on the video's clock, s (used when the poses have times).
  double timeS = 0.0;
  /// Why, for people (e.g. "SfM did not register it").
  std::string reason;
};

/**
 * @brief A frame whose pose is sent, but which its tracker does not vouch for
 * (tracking degraded: the pose agrees with the features, but nothing has
 * checked them against the CT lately).
 */
struct DegradedPose
{
  int frameId = 0;
  /// Why, for people (e.g. "features cast from a prediction").
  std::string reason;
};

/// @brief A frame's picture as the registration saw it: 8-bit RGB, rows top first.
struct FramePicture
{
  int widthPx = 0;
  int heightPx = 0;
  /// widthPx * heightPx * 3 bytes, row after row from the top.
  std::vector<unsigned char> rgb;
};

/// @brief What a pose server sends: the poses of one registration (or of a pose file).
struct ServedPoses
{
  /// T, SfM frame to CT frame, sent as `CTFromSfM`; none when only camera poses are known.
  std::optional<SimilarityTransform> ctFromSfm;
  /// Camera-to-CT pose of every frame, in the order of the video.
  std::vector<FramePose> cameraToCT;
  /// Time of each pose's frame on the video's clock, s, in the same order;
  /// empty when unknown (a pose file): the poses then all carry the time of
  /// their publication.
  std::vector<double> frameTimesS;
  /// Per pose (in the order of cameraToCT), its frame's picture, sent as an
  /// IMAGE message just before the pose, with its time; empty: no pictures.
  std::vector<FramePicture> pictures;
  /// The frames without a pose, in the order of the video: each is told as a
  /// STATUS "TrackingLost" between the poses around it.
  std::vector<FrameWithoutPose> framesWithoutPose;
  /// The poses among cameraToCT (by frame id) that are sent but not vouched
  /// for: each is followed by a STATUS "TrackingDegraded".
  std::vector<DegradedPose> degradedPoses;
  /// The registration's verdict; none for poses that no registration judged.
  std::optional<PoseVerdict> verdict;
};

} // namespace vimlop

#endif
