#ifndef vimlop_ColmapTextModel_h
#define vimlop_ColmapTextModel_h

// Private to the Video module (not installed).

#include <vimlop/Video/ColmapModel.h>

#include <string>

namespace vimlop::detail
{

/// Read COLMAP's text cameras, images and points3D files into `model`;
/// they throw the Error of `path` when it is missing, truncated or malformed.
void readCamerasText(const std::string& path, ColmapModel& model);
void readImagesText(const std::string& path, ColmapModel& model);
void readPointsText(const std::string& path, ColmapModel& model);

} // namespace vimlop::detail

#endif
