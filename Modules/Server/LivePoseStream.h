#ifndef vimlop_LivePoseStream_h
#define vimlop_LivePoseStream_h

#include <vimlop/Server/PoseStreamServer.h>

#include <string>

namespace vimlop
{

/**
 * @brief Poses sent over OpenIGTLink one frame at a time, as a tracker
 * computes them (`vimlop track --serve`).
 *
 * Each frame is one publication of PoseStreamServer: a TRANSFORM of the
 * moving camera (or VideoCamera_<frame id>), stamped with the moment it is
 * sent (the tracker's latency after its frame arrived, so stamps increase
 * frame after frame), followed by a STATUS `TrackingDegraded` when the
 * tracker does not vouch for it; a frame without a pose is a STATUS
 * `TrackingLost` alone. A client that connects mid-stream receives the last
 * frame, then every new one. The server is served between frames (pump()),
 * so it never waits on a client: a client that does not keep up is dropped
 * as PoseStreamServer says, with a warning on stderr.
 */
class LivePoseStream
{
public:
  /**
   * @brief Listens and announces one line on stdout: `<label>: streaming
   * camera poses as <device> on <host>:<port> (OpenIGTLink ...)`.
   * @throws vimlop::Error when the server cannot listen (see PoseStreamServer).
   */
  LivePoseStream(const PoseStreamServerOptions& options, const std::string& label);

  /// @brief The port listened on.
  int port() const { return this->Server.port(); }

  /// @brief Serves until a client is connected or `timeoutS` has passed;
  /// true when one is connected.
  bool waitForClient(double timeoutS);

  /**
   * @brief Sends one frame's pose; a non-empty `degradedReason` follows it
   * with a STATUS TrackingDegraded that says why.
   * @throws vimlop::Error for a pose PoseStreamServer::publish() refuses.
   */
  void sendPose(const FramePose& cameraToCT, const std::string& degradedReason = std::string());

  /// @brief Sends a STATUS TrackingLost for a frame without a pose.
  void sendLost(int frameId, const std::string& reason);

  /// @brief Serves until every client has taken what was sent, at most
  /// `timeoutS`; true when all was taken.
  bool finish(double timeoutS);

  /// @brief Clients connected now.
  int clientCount() const { return this->Server.clientCount(); }

private:
  void send(const ServedPoses& frame);

  PoseStreamServer Server;
};

} // namespace vimlop

#endif
