#include "ErrorMessage.h"
#include <vimlop/Server/PoseStreamServer.h>

#include <gtest/gtest.h>

#include <chrono>
#include <limits>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

using namespace vimlop;

namespace
{

PoseStreamServerOptions anyFreePort()
{
  PoseStreamServerOptions options;
  options.port = 0;
  return options;
}

std::vector<FramePose> twoPoses()
{
  std::vector<FramePose> poses(2);
  poses[0].frameId = 0;
  poses[1].frameId = 1;
  poses[1].cameraToWorld.centre = Eigen::Vector3d(120.0, 100.0, 20.0);
  return poses;
}

} // namespace

TEST(PoseStreamServer, PublishesPosesInsideACT)
{
  PoseStreamServer server(anyFreePort());
  EXPECT_GT(server.port(), 0);
  SimilarityTransform ctFromSfm;
  ctFromSfm.scale = 0.5;
  EXPECT_NO_THROW(server.publish(&ctFromSfm, twoPoses()));
  EXPECT_NO_THROW(server.publish(nullptr, {}));
}

TEST(PoseStreamServer, RefusesToPublishARepeatedIdOrAPoseBeyondFloats)
{
  PoseStreamServer server(anyFreePort());
  std::vector<FramePose> poses = twoPoses();
  poses[1].frameId = 0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(nullptr, poses); }),
    "pose server: refusing to publish: pose 1: frame id 0 repeats pose 0's");
  poses = twoPoses();
  poses[0].cameraToWorld.centre.z() = 4e38; // -inf as the protocol's float
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(nullptr, poses); }),
    "pose server: refusing to publish: pose 0: the camera of frame 0 lies 4e+38 mm from the "
    "origin, farther than 1 km: not a pose in a CT");
  SimilarityTransform ctFromSfm;
  ctFromSfm.translation.x() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(&ctFromSfm, twoPoses()); }),
    "pose server: refusing to publish: CTFromSfM is not a finite similarity within 1 km of the "
    "CT origin");
}

namespace
{

/// A loopback connection to `port` that never reads.
int connectTo(int port)
{
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  return fd;
}

/// Serves for about `ms` milliseconds.
void serveFor(PoseStreamServer& server, int ms)
{
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  server.serve([&] { return std::chrono::steady_clock::now() < end; });
}

} // namespace

TEST(PoseStreamServer, ARefusedConnectionAndADroppedClientAreToldNotSilent)
{
  std::vector<std::string> notices;
  PoseStreamServerOptions options = anyFreePort();
  options.maxClients = 1;
  options.maxPendingBytes = 4096;
  options.onNotice = [&](const std::string& text) { notices.push_back(text); };
  PoseStreamServer server(options);
  server.publish(nullptr, twoPoses());
  const int reader = connectTo(server.port());
  serveFor(server, 100);
  std::vector<int> refused;
  for (int i = 0; i < 12; ++i)
  {
    refused.push_back(connectTo(server.port()));
  }
  serveFor(server, 300);
  EXPECT_EQ(server.clientCount(), 1);
  EXPECT_EQ(server.refusedCount(), 12);
  // Told at the 1st and the 10th refusal, not at every one.
  ASSERT_EQ(notices.size(), 2u);
  EXPECT_EQ(
    notices[1], "refused a connection (10 so far): 1 clients are served at once (--max-clients)");
  notices.erase(notices.begin() + 1);
  EXPECT_EQ(
    notices[0], "refused a connection (1 so far): 1 clients are served at once (--max-clients)");
  // The client never reads: publishing again and again fills its socket,
  // then its 4 KiB of pending poses, and it is dropped with a word.
  for (int i = 0; i < 100000 && server.clientCount() == 1; ++i)
  {
    server.publish(nullptr, twoPoses());
  }
  EXPECT_EQ(server.clientCount(), 0);
  EXPECT_EQ(server.droppedCount(), 1);
  ASSERT_EQ(notices.size(), 2u);
  EXPECT_EQ(notices[1].rfind("dropped a client that does not keep up: ", 0), 0u) << notices[1];
  close(reader);
  for (int fd : refused)
  {
    close(fd);
  }
}

TEST(PoseStreamServer, AClientThatStopsReadingIsDroppedAfterTheStallTimeout)
{
  std::vector<std::string> notices;
  PoseStreamServerOptions options = anyFreePort();
  options.maxPendingBytes = 64 << 20; // the stall, not the size, drops it here
  options.stallTimeoutS = 0.2;
  options.onNotice = [&](const std::string& text) { notices.push_back(text); };
  PoseStreamServer server(options);
  const int sleeper = connectTo(server.port());
  serveFor(server, 100);
  ASSERT_EQ(server.clientCount(), 1);
  // 40 000 publications (8 MB) overflow the loopback socket buffers.
  for (int i = 0; i < 40000; ++i)
  {
    server.publish(nullptr, twoPoses());
  }
  serveFor(server, 600);
  EXPECT_EQ(server.clientCount(), 0);
  EXPECT_EQ(server.droppedCount(), 1);
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_EQ(notices[0].rfind("dropped a client that stopped reading: ", 0), 0u) << notices[0];
  close(sleeper);
}

TEST(PoseStreamServer, TheDefaultServesHundredsOfClientsAndRaisesItsDescriptorLimit)
{
  EXPECT_EQ(PoseStreamServerOptions().maxClients, 512);
  PoseStreamServerOptions options = anyFreePort();
  options.maxClients = 1 << 30;
  EXPECT_EQ(fixtures::errorMessageOf([&] { PoseStreamServer server(options); })
              .find("serving 1073741824 clients needs 1073741888 file descriptors; this process "
                    "may open "),
    0u);
}
