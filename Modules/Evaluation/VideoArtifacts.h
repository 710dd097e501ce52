#ifndef vimlop_VideoArtifacts_h
#define vimlop_VideoArtifacts_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/DepthMap.h>
#include <vimlop/Core/PinholeCamera.h>

#include <opencv2/core/mat.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief The lossy codecs a simulated sequence can be passed through.
enum class VideoCompression
{
  None, ///< no compression (the default)
  Mjpg, ///< Motion JPEG in .avi (OpenCV's own MJPEG writer, whose quality can be set)
  H264, ///< H.264 in .mp4 (FFmpeg backend, libx264; bitrate chosen by OpenCV)
  Mp4v  ///< MPEG-4 part 2 in .mp4 (FFmpeg backend; bitrate chosen by OpenCV)
};

/// @brief The codec's name as the command line spells it: none, mjpg, h264, mp4v.
std::string videoCompressionName(VideoCompression codec);

/**
 * @brief The artifacts of real endoscope video: motion blur, specular
 * highlights, exposure, shot noise, lossy compression and occluders (fluid,
 * blood on the lens).
 *
 * Each is off by default, so that the default sequence stays the ideal world
 * bit for bit. Realistic values and their sources: Documentation/Simulation.md.
 */
struct VideoArtifactOptions
{
  /// Exposure time of each frame, s (default 0: no motion blur). The frame
  /// integrates the picture while the camera moves, centred on the frame's
  /// time. Realistic: 1/60 to 1/30 s for 30 fps endoscope video (an
  /// estimate: endoscope cameras expose for most of the frame period in dim
  /// light). At most 1 s.
  double exposureTimeS = 0.0;
  /// Number of instants at which the motion blur samples the exposure
  /// (default 7; 2 to 64).
  int motionBlurSamples = 7;
  /// Specular highlights: the light added where the surface mirrors the tip's
  /// light back into the lens, as a fraction of full scale (255 grey levels)
  /// at the highlight's centre (default 0: none). Realistic: 1 to 2, the wet
  /// mucosa's highlights saturate the sensor (an estimate). At most 10.
  double specularStrength = 0.0;
  /// Angle between the surface normal and the direction back to the camera
  /// within which a highlight is seen, degrees (default 8; wet mucosa is
  /// glossy, not a mirror: 5 to 10, an estimate). In (0, 45].
  double specularAngleDeg = 8.0;
  /// Exposure gain: the light is multiplied by it and clipped to [0, 255]
  /// before the sensor noise (default 1: as rendered). Realistic: 0.6 to 1.6,
  /// the auto-exposure of an endoscope camera lags the scope's motion (an
  /// estimate). In (0, 10].
  double exposureGain = 1.0;
  /// Shot noise: its variance is this times the pixel's value, grey levels
  /// (grey levels per photo-electron; default 0: none). Realistic: 0.05 to
  /// 0.5 (an estimate: 255 grey levels over a full well of a few thousand
  /// electrons, raised by the camera's analogue gain in dim light). At most 10.
  double shotNoise = 0.0;
  /// Lossy compression of the whole sequence (default none). Real endoscopy
  /// recorders store H.264 or Motion JPEG.
  VideoCompression compression = VideoCompression::None;
  /// JPEG quality of mjpg, 1 to 100 (default 0: the writer's own,
  /// which measures as 75).
  /// Realistic: 50 to 90 (an estimate for OR recorders). OpenCV 4.6's FFmpeg
  /// writer has no quality setting, so h264 and mp4v refuse one.
  int compressionQuality = 0;
  /// Fraction of frames with occluders (default 0: none). Realistic: 0.05 to
  /// 0.2 (an estimate: blood, mucus and irrigation fluid cross the lens now
  /// and then in sinus surgery). In [0, 1].
  double occludedFrameFraction = 0.0;
  /// Fraction of an occluded frame's area the occluders cover (default 0.1;
  /// realistic 0.05 to 0.3, an estimate). In (0, 0.9].
  double occluderAreaFraction = 0.1;
  /// Opacity of an occluder at its centre (default 0.8: fluid is
  /// semi-transparent; an estimate). In (0, 1].
  double occluderOpacity = 0.8;
  /// Fraction of frames in stretches where the lens touches the mucosa
  /// (default 0: none). The picture is then a red, featureless blur: the
  /// light passes through the tissue pressed on the window ("red-out"), and
  /// the scope sees little until it is drawn back. Realistic: 0.02 to 0.05
  /// (an estimate: a surgeon brushes the wall now and then in the narrow
  /// nasal cavity and backs off within a second). The pose stays on the
  /// path: a stretch stands for the pictures lost, while the scope moves on
  /// as the path does. In [0, 0.5].
  double wallContactFraction = 0.0;
  /// Frames of each such stretch (default 10, a third of a second at 30
  /// fps; 1 to 300).
  int wallContactFrames = 10;

  /// @brief True when the options change no pixel (the defaults).
  bool isOff() const
  {
    return this->exposureTimeS == 0.0 && this->specularStrength == 0.0 &&
      this->exposureGain == 1.0 && this->shotNoise == 0.0 &&
      this->compression == VideoCompression::None && this->occludedFrameFraction == 0.0 &&
      this->wallContactFraction == 0.0;
  }

  /// @brief True when an artifact acts on the light before the sensor (all but
  /// compression): the frame must then be rendered without noise.
  bool actsOnLight() const
  {
    return this->exposureTimeS != 0.0 || this->specularStrength != 0.0 ||
      this->exposureGain != 1.0 || this->shotNoise != 0.0 || this->occludedFrameFraction != 0.0 ||
      this->wallContactFraction != 0.0;
  }

  /**
   * @brief Checks the settings.
   * @throws vimlop::Error naming the knob and its bad value (a negative,
   * non-finite or out-of-range number, a quality with a codec that has none).
   */
  void validate() const;
};

/**
 * @brief The camera poses at `samples` instants evenly spread over an
 * exposure of `exposureTimeS` centred on frame `frame` of `cameras` (frame f
 * at time f / framesPerSecond): centres linear and rotations spherical-linear
 * between frames, extended at constant velocity beyond the first and last.
 */
std::vector<CameraPose> exposurePoses(const std::vector<CameraPose>& cameras, int frame,
  double framesPerSecond, double exposureTimeS, int samples);

/**
 * @brief Motion blur from the camera's motion: each pixel with a surface in
 * `depth` is back-projected by `camera` from `framePose`, projected from each
 * of `poses` (the exposure, exposurePoses), and the picture is averaged over
 * those points (bilinear): the pixel's flow line during the exposure. Pixels
 * without a surface take the flow of the nearest pixel with one. A picture
 * of any type; the same picture when every pose is `framePose` or no pixel
 * has a surface.
 */
cv::Mat renderMotionBlur(const cv::Mat& picture, const DepthMap& depth, const PinholeCamera& camera,
  const CameraPose& framePose, const std::vector<CameraPose>& poses);

/**
 * @brief The specular highlight seen at each pixel, as a fraction of full
 * scale (CV_32F): with the light at the camera's centre, the surface mirrors
 * it into the lens where its normal points back at the camera; with α that
 * angle and α0 = `angleDeg`, the highlight is strength × (1 − (α / α0)²) for
 * α < α0 and 0 beyond. The normals come from `depth` smoothed over 3 px
 * (the mesh's facets are not the mucosa's shape), back-projected 2 px either
 * side; none within 7 px of where there is no surface or of the image's edge.
 */
cv::Mat specularHighlights(
  const DepthMap& depth, const PinholeCamera& camera, double strength, double angleDeg);

/// @brief Adds the highlights (specularHighlights) to a CV_32FC3 picture, as white light.
void addSpecularHighlights(cv::Mat& light, const cv::Mat& highlights);

/// @brief Multiplies a CV_32FC3 picture by `gain` and clips it to [0, 255].
void applyExposure(cv::Mat& light, double gain);

/**
 * @brief The sensor's noise on a CV_32FC3 picture, rounded to 8 bits: per
 * channel Gaussian with variance sigma² + shotNoise × value (the shot noise
 * of a Poisson count, in its Gaussian form), seeded from `seed`.
 */
cv::Mat addSensorNoise(const cv::Mat& light, double sigma, double shotNoise, std::uint64_t seed);

/**
 * @brief Which of `frames` frames carry occluders: round(fraction × frames)
 * of them, chosen from `seed`.
 */
std::vector<bool> occludedFrames(int frames, double fraction, std::uint64_t seed);

/**
 * @brief The coverage of one frame's occluders (CV_32F, 0 to 1): one to three
 * smooth blobs with wavy outlines and soft edges, seeded from `seed`, scaled
 * so that the pixels of coverage at least 0.5 make `areaFraction` of the image.
 */
cv::Mat occluderCoverage(int widthPx, int heightPx, double areaFraction, std::uint64_t seed);

/**
 * @brief Lays the occluders of `coverage` over a CV_32FC3 picture: the light
 * becomes (1 − c) × light + c × dark red, with c = coverage × opacity.
 */
void applyOccluders(cv::Mat& light, const cv::Mat& coverage, double opacity);

/**
 * @brief Which of `frames` frames lie in stretches of wall contact:
 * stretches of `stretchFrames` frames (the last one cut at the sequence's
 * end), apart from one another, at starts drawn from `seed`, until
 * round(fraction × frames) frames are covered or no room is left. Frame 0
 * is never in one.
 */
std::vector<bool> wallContactFrames(
  int frames, double fraction, int stretchFrames, std::uint64_t seed);

/**
 * @brief The picture of a lens pressed on the mucosa (CV_32FC3): the light
 * of `light` blurred over a fifth of the frame's width, carried through the
 * tissue as red light (green and blue at two fifths and a fifth of red),
 * its red at 1.5 times the picture's mean grey level: no corner and no
 * contour left.
 */
void applyWallContact(cv::Mat& light);

/**
 * @brief Passes 8-bit BGR frames through a lossy codec: writes them to a
 * temporary video file with OpenCV's VideoWriter, reads them back with
 * VideoCapture (FFmpeg) and removes the file. `quality` as
 * VideoArtifactOptions::compressionQuality. VideoCompression::None returns the frames.
 * @throws vimlop::Error if the codec is not available or the file cannot be
 * written or read back whole.
 */
std::vector<cv::Mat> compressVideo(
  const std::vector<cv::Mat>& frames, VideoCompression codec, int quality, double framesPerSecond);

} // namespace vimlop

#endif
