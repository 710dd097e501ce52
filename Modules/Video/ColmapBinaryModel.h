#ifndef vimlop_ColmapBinaryModel_h
#define vimlop_ColmapBinaryModel_h

// Private to the Video module (not installed).

#include <vimlop/Video/ColmapModel.h>

#include <string>

namespace vimlop::detail
{

/// Read COLMAP's binary cameras, images and points3D files into `model`;
/// they throw the Error of `path` when it is missing, truncated or malformed.
void readCamerasBinary(const std::string& path, ColmapModel& model);
void readImagesBinary(const std::string& path, ColmapModel& model);
void readPointsBinary(const std::string& path, ColmapModel& model);

} // namespace vimlop::detail

#endif
