#ifndef vimlop_RegisteredVideo_h
#define vimlop_RegisteredVideo_h

#include <vimlop/Results/RegistrationRecord.h>

#include "VIMLOPReportModule.h"

#include <functional>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief Writes the registered video of a result folder: for every frame, the
 * frame with the model's occluding contours at its registered pose (green)
 * and its video contours (white), beside the airway rendered offscreen from
 * that pose, under a band stating the verdict (RegistrationVerdict: green
 * registered, red flagged as a failure, amber not checked). PNG frames in `folder/registered/` and,
 * with OpenCV's MJPEG writer, `folder/registered-video.avi` at `fps`. The frame pictures named by
 * record.frameImages must be in `folder`. Needs an X display. `keepGoing`,
 * when given, is asked before each frame: false stops the video there.
 * @return the files written, relative to `folder`.
 * @throws vimlop::Error if a file cannot be written.
 */
VIMLOPREPORT_EXPORT std::vector<std::string> writeRegisteredVideo(const RegistrationRecord& record,
  const std::string& folder, double fps, const std::function<bool()>& keepGoing = {});

/**
 * @brief Writes the registered camera path (a polyline through the optical
 * centres, CT frame, mm, with a "FrameId" point array) as `path` (.vtp).
 * @throws vimlop::Error if the file cannot be written.
 */
VIMLOPREPORT_EXPORT void writeCameraPath(const RegistrationResult& result, const std::string& path);

} // namespace vimlop

#endif
