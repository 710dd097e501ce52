#ifndef vimlop_FieldOfViewOptions_h
#define vimlop_FieldOfViewOptions_h

#include <string>

/**
 * @file FieldOfViewOptions.h
 * @brief How the main job finds the part of the frames that shows anatomy
 * (inside the endoscope's field stop), apart from OpenCV so that option
 * structs holding it stay light.
 */
namespace vimlop
{

/// @brief Where the field stop (the black disc border of an endoscope's frames) comes from.
enum class FieldStopMode
{
  /// No field stop: every pixel shows anatomy.
  None,
  /// Detected from the frames: the dark border that does not move. Frames
  /// without such a border give "every pixel valid", so an ideal sequence
  /// is processed exactly as with None.
  Auto,
  /// A mask image file, white (non-zero) inside the field stop.
  File,
  /// A circle given by its centre and radius.
  Circle
};

/// @brief Settings of the field of view (FieldOfView::ofSequence); pixels and 8-bit grey levels.
struct FieldOfViewOptions
{
  /// Where the field stop comes from (default Auto: it changes nothing on
  /// frames without a dark border, and a real endoscope's frames have one).
  FieldStopMode mode = FieldStopMode::Auto;
  /// The mask image of File mode, white inside (default empty).
  std::string maskFile;
  /// Circle mode: the centre, pixels (u right, v down from the top-left
  /// pixel's centre) and the radius, pixels (defaults 0: must be given).
  double centreUPx = 0.0;
  double centreVPx = 0.0;
  double radiusPx = 0.0;
  /// Pixels within this distance of the field stop's edge are invalid too,
  /// pixels (default 12): it covers the edge's softness (1-2 px), the
  /// detector's smoothing (about 3 sigma at twice 1.2 px for the scale
  /// test) and its farthest dark-side probe (7 px), which would otherwise
  /// see the black border as the dark side of an occluding contour.
  double marginPx = 12.0;
  /// Auto mode: a pixel whose brightest value over the frames (after a 5 px
  /// median that removes sensor noise) stays at or below this is border,
  /// 8-bit grey levels (default 20: well above a sensor's black level and
  /// noise, well below vignetted anatomy, which over many frames is lit
  /// somewhere).
  double autoThresholdGrey = 20.0;
  /// Auto mode: a dark border covering less than this fraction of the frame
  /// is no field stop (default 0.01): a few dark corner pixels of an
  /// ideal sequence must not change its result.
  double autoMinBorderFraction = 0.01;

  /**
   * @brief The options of a text form: `none`, `auto`, `circle:U,V,R`
   * (centre and radius, pixels) or the path of a mask image; the margin
   * and thresholds are those of `base`.
   * @throws vimlop::Error for a malformed circle.
   */
  static FieldOfViewOptions fromText(const std::string& text, const FieldOfViewOptions& base);
  /// @brief The text form fromText() reads.
  std::string toText() const;
};

/// @brief "none", "auto", "file" or "circle".
const char* fieldStopModeName(FieldStopMode mode);

} // namespace vimlop

#endif
