#include <vimlop/Server/LivePoseStream.h>

#include <chrono>
#include <cstdio>

namespace vimlop
{

namespace
{

/// Serves `server` until `done()` or `timeoutS`; returns done().
template <typename Done>
bool serveUntil(PoseStreamServer& server, double timeoutS, Done done)
{
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutS);
  while (!done() && std::chrono::steady_clock::now() < end)
  {
    server.pump(20);
  }
  return done();
}

} // namespace

LivePoseStream::LivePoseStream(const PoseStreamServerOptions& options, const std::string& label)
  : Server(withNoticesOnStderr(options, label))
{
  const std::string device = options.cameraNames == CameraDeviceNames::OneMovingCamera
    ? options.cameraName
    : std::string("VideoCamera_<id>");
  std::printf("%s: streaming camera poses as %s on %s:%d (OpenIGTLink TRANSFORM, RAS mm; STATUS "
              "TrackingDegraded and TrackingLost)\n",
    label.c_str(), device.c_str(), options.host.c_str(), this->Server.port());
  std::fflush(stdout);
}

bool LivePoseStream::waitForClient(double timeoutS)
{
  return serveUntil(this->Server, timeoutS, [this] { return this->Server.clientCount() > 0; });
}

void LivePoseStream::send(const ServedPoses& frame)
{
  this->Server.publish(frame);
  this->Server.pump(0);
}

void LivePoseStream::sendPose(const FramePose& cameraToCT, const std::string& degradedReason)
{
  ServedPoses frame;
  frame.cameraToCT = { cameraToCT };
  if (!degradedReason.empty())
  {
    frame.degradedPoses = { { cameraToCT.frameId, degradedReason } };
  }
  this->send(frame);
}

void LivePoseStream::sendLost(int frameId, const std::string& reason)
{
  ServedPoses frame;
  frame.framesWithoutPose = { { frameId, 0.0, reason } };
  this->send(frame);
}

bool LivePoseStream::finish(double timeoutS)
{
  return serveUntil(this->Server, timeoutS, [this] { return this->Server.allSent(); });
}

} // namespace vimlop
