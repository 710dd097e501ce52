#ifndef vimlop_PoseServing_h
#define vimlop_PoseServing_h

#include <vimlop/Server/PoseStreamServer.h>
#include <vimlop/Server/ServedPoses.h>

#include <functional>
#include <string>

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
  /// Serve a result the registration flagged as a failure (default false:
  /// refused, since a navigation display would show it like any other).
  /// Clients are still told by the STATUS message.
  bool allowFlagged = false;
};

/// @brief T and every frame's camera-to-CT pose of a registration result
/// (no frame times, no verdict: RegistrationResult holds neither).
ServedPoses servedPosesOf(const RegistrationResult& result);

/**
 * @brief Listens, announces on stdout one line with the address (`<label>:
 * ... on <host>:<port> ...`), sends `poses` to every client that connects and
 * returns when Ctrl-C or SIGTERM arrives, the duration has passed or
 * `options.keepServing` says to stop, after a
 * closing line. The signal handlers are restored on return.
 * @throws vimlop::Error when the server cannot listen or publish (see
 * PoseStreamServer), or for flagged poses without `options.allowFlagged`.
 */
void servePoses(const PoseServingOptions& options, const ServedPoses& poses);

} // namespace vimlop

#endif
