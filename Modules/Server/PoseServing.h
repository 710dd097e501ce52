#ifndef vimlop_PoseServing_h
#define vimlop_PoseServing_h

#include <vimlop/Core/FramePose.h>
#include <vimlop/Core/SimilarityTransform.h>
#include <vimlop/Server/PoseStreamServer.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

struct RegistrationResult;

/**
 * @file PoseServing.h
 * @brief Serving poses over OpenIGTLink until the user stops it: what `vimlop
 * serve` does, shaped so that any command that ends with poses (e.g. a
 * registration) can serve them the same way.
 */

/// @brief How poses are served: the server's address and limits, and for how long.
struct PoseServingOptions
{
  PoseStreamServerOptions server;
  /// Stop after this many seconds (default 0: until Ctrl-C or SIGTERM).
  double durationS = 0.0;
  /// What the announcement and the closing line start with (default "vimlop serve").
  std::string label = "vimlop serve";
  /// Also stop when this returns false (asked about every 100 ms); empty: never asked.
  std::function<bool()> keepServing;
};

/// @brief What is served.
struct ServedPoses
{
  /// T, SfM frame to CT frame, sent as `CTFromSfM`; none when only camera poses are known.
  std::optional<SimilarityTransform> ctFromSfm;
  /// Camera-to-CT pose of every frame, each sent as `VideoCamera_<frame id>`.
  std::vector<FramePose> cameraToCT;
};

/// @brief T and every frame's camera-to-CT pose of a registration result.
ServedPoses servedPosesOf(const RegistrationResult& result);

/**
 * @brief Listens, announces on stdout one line with the address (`<label>:
 * ... on <host>:<port> ...`), sends `poses` to every client that connects and
 * returns when Ctrl-C or SIGTERM arrives, the duration has passed or
 * `options.keepServing` says to stop, after a
 * closing line. The signal handlers are restored on return.
 * @throws vimlop::Error when the server cannot listen (see PoseStreamServer).
 */
void servePoses(const PoseServingOptions& options, const ServedPoses& poses);

} // namespace vimlop

#endif
