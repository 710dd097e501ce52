#ifndef vimlop_ColmapCameraModel_h
#define vimlop_ColmapCameraModel_h

// Private to the Video module (not installed).

#include <vimlop/Core/PinholeCamera.h>

#include <cstdint>
#include <string>
#include <vector>

namespace vimlop::detail
{

/// Name, parameter count and COLMAP id of the camera models VIMLOP reads.
struct ColmapCameraModel
{
  const char* name;
  int id;
  int parameters;
};

/// The supported camera model of a name or a COLMAP id; throws the Error of
/// `path` for the others, naming the supported ones.
const ColmapCameraModel& modelByName(const std::string& path, const std::string& name);
const ColmapCameraModel& modelById(const std::string& path, int id);

/// Images larger than this on a side are not endoscope frames; such sizes
/// come from corrupt files (and would overflow pixel counts downstream).
inline constexpr std::int64_t maxImageSidePx = 1 << 16;

/// COLMAP parameters to VIMLOP intrinsics: pixel centres move from 0.5 to 0.
/// Refuses sizes and parameters that no camera has (NaN, zero focal length).
PinholeCamera intrinsicsOf(const std::string& path, std::uint64_t cameraId,
  const ColmapCameraModel& model, const std::vector<double>& p, std::int64_t width,
  std::int64_t height);

} // namespace vimlop::detail

#endif
