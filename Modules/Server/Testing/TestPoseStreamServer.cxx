#include "ErrorMessage.h"
#include <vimlop/Server/LivePoseStream.h>
#include <vimlop/Server/PoseStreamServer.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

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

/// Camera poses alone, as a pose file gives them.
ServedPoses only(const std::vector<FramePose>& cameraToCT)
{
  ServedPoses poses;
  poses.cameraToCT = cameraToCT;
  return poses;
}

} // namespace

TEST(PoseStreamServer, PublishesPosesInsideACT)
{
  PoseStreamServer server(anyFreePort());
  EXPECT_GT(server.port(), 0);
  SimilarityTransform ctFromSfm;
  ctFromSfm.scale = 0.5;
  ServedPoses poses = only(twoPoses());
  poses.ctFromSfm = ctFromSfm;
  EXPECT_NO_THROW(server.publish(poses));
  EXPECT_NO_THROW(server.publish(ServedPoses()));
}

TEST(PoseStreamServer, RefusesToPublishARepeatedIdOrAPoseBeyondFloats)
{
  PoseStreamServer server(anyFreePort());
  std::vector<FramePose> poses = twoPoses();
  poses[1].frameId = 0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(only(poses)); }),
    "pose server: refusing to publish: pose 1: frame id 0 repeats pose 0's");
  poses = twoPoses();
  poses[0].cameraToWorld.centre.z() = 4e38; // -inf as the protocol's float
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(only(poses)); }),
    "pose server: refusing to publish: pose 0: the camera of frame 0 lies 4e+38 mm from the "
    "origin, farther than 1 km: not a pose in a CT");
  SimilarityTransform ctFromSfm;
  ctFromSfm.translation.x() = std::numeric_limits<double>::infinity();
  ServedPoses withT = only(twoPoses());
  withT.ctFromSfm = ctFromSfm;
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(withT); }),
    "pose server: refusing to publish: CTFromSfM is not a finite similarity within 1 km of the "
    "CT origin");
}

namespace
{

/// A loopback connection to `port` that never reads.
/// Connects from `from`, a loopback address of the 127/8 block.
int connectTo(int port, const char* from = "127.0.0.1")
{
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in source{};
  source.sin_family = AF_INET;
  inet_pton(AF_INET, from, &source.sin_addr);
  EXPECT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&source), sizeof(source)), 0) << from;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  return fd;
}

/// True when the server has closed the connection (its data read to the end).
bool closedByServer(int fd)
{
  char buffer[4096];
  for (;;)
  {
    const ssize_t got = recv(fd, buffer, sizeof(buffer), MSG_DONTWAIT);
    if (got <= 0)
    {
      return got == 0;
    }
  }
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
  server.publish(only(twoPoses()));
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
    server.publish(only(twoPoses()));
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

TEST(PoseStreamServer, OnePublicationLargerThanThePendingLimitReachesAClientWhole)
{
  // A client that connects or reads while a large publication goes out was
  // dropped at once: that publication alone was above the limit.
  PoseStreamServerOptions options = anyFreePort();
  options.maxPendingBytes = 4096;
  PoseStreamServer server(options);
  const int reader = connectTo(server.port());
  serveFor(server, 100);
  ASSERT_EQ(server.clientCount(), 1);
  std::vector<FramePose> many(40000); // 4.2 MB, more than a loopback socket takes at once
  for (int i = 0; i < 40000; ++i)
  {
    many[i].frameId = i;
  }
  server.publish(only(many));
  const std::size_t expected = 40000 * (58 + 48); // OpenIGTLink header + TRANSFORM body
  std::size_t received = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  server.serve(
    [&]
    {
      char buffer[1 << 16];
      for (ssize_t got = 0; (got = recv(reader, buffer, sizeof(buffer), MSG_DONTWAIT)) > 0;)
      {
        received += static_cast<std::size_t>(got);
      }
      return received < expected && std::chrono::steady_clock::now() < end;
    });
  EXPECT_EQ(received, expected);
  EXPECT_EQ(server.droppedCount(), 0);
  EXPECT_EQ(server.clientCount(), 1);
  close(reader);
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
    server.publish(only(twoPoses()));
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

TEST(PoseStreamServer, ManyConnectionsFromOneAddressReplaceItsMostIdleAndLeaveOthersAlone)
{
  std::vector<std::string> notices;
  PoseStreamServerOptions options = anyFreePort();
  options.maxClientsPerAddress = 3;
  options.onNotice = [&](const std::string& text) { notices.push_back(text); };
  PoseStreamServer server(options);
  server.publish(only(twoPoses()));
  const int navigation = connectTo(server.port(), "127.0.0.1");
  serveFor(server, 100);
  std::vector<int> crowd;
  for (int i = 0; i < 5; ++i)
  {
    crowd.push_back(connectTo(server.port(), "127.0.0.2"));
    serveFor(server, 50); // one at a time, so that their order is known
  }
  serveFor(server, 200);
  EXPECT_EQ(server.clientCount(), 4);
  EXPECT_EQ(server.replacedCount(), 2);
  EXPECT_EQ(server.refusedCount(), 0);
  // All took their poses at once: the oldest two of 127.0.0.2 made room.
  EXPECT_TRUE(closedByServer(crowd[0]));
  EXPECT_TRUE(closedByServer(crowd[1]));
  for (int i = 2; i < 5; ++i)
  {
    EXPECT_FALSE(closedByServer(crowd[static_cast<size_t>(i)])) << i;
  }
  EXPECT_FALSE(closedByServer(navigation));
  ASSERT_EQ(notices.size(), 1u); // told at the 1st, the 10th ...
  EXPECT_EQ(notices[0],
    "closed a connection from 127.0.0.2 (1 so far): 3 are kept per address "
    "(--max-clients-per-address); its most idle one made room for the new one");
  close(navigation);
  for (int fd : crowd)
  {
    close(fd);
  }
}

TEST(PoseStreamServer, OnlyAllowedAddressesConnectWhenAListIsGiven)
{
  std::vector<std::string> notices;
  PoseStreamServerOptions options = anyFreePort();
  options.allowedClients = { "127.0.0.2", "127.0.1.0/24" };
  options.onNotice = [&](const std::string& text) { notices.push_back(text); };
  PoseStreamServer server(options);
  server.publish(only(twoPoses()));
  const int listed = connectTo(server.port(), "127.0.0.2");
  const int inBlock = connectTo(server.port(), "127.0.1.77");
  const int local = connectTo(server.port(), "127.0.0.1");
  const int outside = connectTo(server.port(), "127.0.2.1");
  serveFor(server, 300);
  EXPECT_EQ(server.clientCount(), 2);
  EXPECT_EQ(server.refusedCount(), 2);
  EXPECT_FALSE(closedByServer(listed));
  EXPECT_FALSE(closedByServer(inBlock));
  EXPECT_TRUE(closedByServer(local));
  EXPECT_TRUE(closedByServer(outside));
  ASSERT_GE(notices.size(), 1u);
  EXPECT_EQ(notices[0].rfind("refused a connection (1 so far): 127.0.", 0), 0u) << notices[0];
  EXPECT_NE(notices[0].find(" is not an allowed client (--allow-client)"), std::string::npos)
    << notices[0];
  for (int fd : { listed, inBlock, local, outside })
  {
    close(fd);
  }
}

TEST(PoseStreamServer, RefusesAnAllowListEntryThatIsNotAnAddressOrBlock)
{
  for (const char* entry : { "300.1.1.1", "10.0.0.0/33", "10.0.0.0/", "10.0.0.0/8x", "host" })
  {
    PoseStreamServerOptions options = anyFreePort();
    options.allowedClients = { entry };
    EXPECT_EQ(fixtures::errorMessageOf([&] { PoseStreamServer server(options); }),
      "'" + std::string(entry) +
        "' is not an IPv4 address or block to allow (a.b.c.d, or a.b.c.d/n with n at most 32)");
  }
  PoseStreamServerOptions none = anyFreePort();
  none.maxClientsPerAddress = 0;
  EXPECT_EQ(fixtures::errorMessageOf([&] { PoseStreamServer server(none); }),
    "the port must lie in [0, 65535], at least one client (and one per address) must be allowed "
    "and the stall timeout must be positive");
}

namespace
{

/// One OpenIGTLink message as a receiver sees it (header fields, body bytes).
struct WireMessage
{
  std::string type;
  std::string device;
  double timeS = 0.0;
  std::string body;
};

std::uint64_t bigEndian(const std::string& bytes, size_t at, int count)
{
  std::uint64_t value = 0;
  for (int i = 0; i < count; ++i)
  {
    value = (value << 8) | static_cast<unsigned char>(bytes[at + static_cast<size_t>(i)]);
  }
  return value;
}

std::string field(const std::string& bytes, size_t at, size_t length)
{
  const std::string raw = bytes.substr(at, length);
  return raw.substr(0, raw.find('\0'));
}

/// What has arrived on `fd`, cut into messages by the protocol's 58-byte
/// header (version, type, device, time, body size, CRC); closes `fd`.
std::vector<WireMessage> messagesArrivedOn(int fd)
{
  std::string bytes;
  char buffer[4096];
  for (ssize_t got = 0; (got = recv(fd, buffer, sizeof(buffer), MSG_DONTWAIT)) > 0;)
  {
    bytes.append(buffer, static_cast<size_t>(got));
  }
  close(fd);
  std::vector<WireMessage> messages;
  for (size_t at = 0; at + 58 <= bytes.size();)
  {
    WireMessage m;
    m.type = field(bytes, at + 2, 12);
    m.device = field(bytes, at + 14, 20);
    m.timeS = static_cast<double>(bigEndian(bytes, at + 34, 4)) +
      static_cast<double>(bigEndian(bytes, at + 38, 4)) / 4294967296.0;
    const size_t bodySize = bigEndian(bytes, at + 42, 8);
    m.body = bytes.substr(at + 58, bodySize);
    messages.push_back(m);
    at += 58 + bodySize;
  }
  return messages;
}

/// Everything `server` sends one new client within `ms`.
std::vector<WireMessage> receiveAll(PoseStreamServer& server, int ms)
{
  const int fd = connectTo(server.port());
  serveFor(server, ms);
  return messagesArrivedOn(fd);
}

double wallClockS()
{
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

ServedPoses threeFramesOfAVideo()
{
  ServedPoses poses;
  poses.cameraToCT.resize(3);
  for (int i = 0; i < 3; ++i)
  {
    poses.cameraToCT[static_cast<size_t>(i)].frameId = 10 + i;
  }
  poses.frameTimesS = { 0.4, 0.44, 0.48 };
  poses.ctFromSfm = SimilarityTransform();
  return poses;
}

} // namespace

TEST(PoseStreamServer, OneMovingCameraCarriesTheVideoTimesEndingAtThePublication)
{
  PoseStreamServer server(anyFreePort());
  const double beforeS = wallClockS();
  server.publish(threeFramesOfAVideo());
  const double afterS = wallClockS();
  const std::vector<WireMessage> got = receiveAll(server, 200);
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(got[0].device, "CTFromSfM");
  for (size_t i = 1; i < 4; ++i)
  {
    EXPECT_EQ(got[i].type, "TRANSFORM");
    EXPECT_EQ(got[i].device, "CameraToCT") << i;
  }
  // The newest frame at the moment of publication, the others 40 and 80 ms before it.
  EXPECT_GE(got[3].timeS, beforeS - 1e-6);
  EXPECT_LE(got[3].timeS, afterS + 1e-6);
  EXPECT_NEAR(got[3].timeS - got[2].timeS, 0.04, 1e-6);
  EXPECT_NEAR(got[2].timeS - got[1].timeS, 0.04, 1e-6);
  EXPECT_NEAR(got[0].timeS, got[3].timeS, 1e-6);
}

TEST(PoseStreamServer, PosesWithoutTimesAllCarryTheirPublicationsTime)
{
  PoseStreamServer server(anyFreePort());
  const double beforeS = wallClockS();
  server.publish(only(twoPoses()));
  const std::vector<WireMessage> got = receiveAll(server, 200);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_GE(got[0].timeS, beforeS - 1e-6);
  EXPECT_EQ(got[0].timeS, got[1].timeS);
}

TEST(PoseStreamServer, PerFrameNamesGiveEachFrameItsOwnDevice)
{
  PoseStreamServerOptions options = anyFreePort();
  options.cameraNames = CameraDeviceNames::OnePerFrame;
  PoseStreamServer server(options);
  server.publish(threeFramesOfAVideo());
  const std::vector<WireMessage> got = receiveAll(server, 200);
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(got[1].device, "VideoCamera_10");
  EXPECT_EQ(got[3].device, "VideoCamera_12");
}

TEST(PoseStreamServer, TheVerdictFollowsThePosesAsAStatusMessage)
{
  PoseStreamServerOptions options = anyFreePort();
  options.cameraName = "Endoscope";
  PoseStreamServer server(options);
  for (const bool flagged : { false, true })
  {
    ServedPoses poses = threeFramesOfAVideo();
    poses.verdict = PoseVerdict{ flagged, flagged ? "contour error 9.0 px" : "ok" };
    server.publish(poses);
    const std::vector<WireMessage> got = receiveAll(server, 200);
    ASSERT_EQ(got.size(), 5u);
    EXPECT_EQ(got[3].device, "Endoscope");
    const WireMessage& status = got[4];
    EXPECT_EQ(status.type, "STATUS");
    EXPECT_EQ(status.device, "Endoscope");
    // Body: code (2 bytes), subcode (8), error name (20), status text.
    EXPECT_EQ(bigEndian(status.body, 0, 2), flagged ? 2u : 1u);
    EXPECT_EQ(field(status.body, 10, 20), flagged ? "RegistrationFlagged" : "");
    EXPECT_EQ(
      field(status.body, 30, status.body.size() - 30), flagged ? "contour error 9.0 px" : "ok");
  }
}

TEST(PoseStreamServer, ListensOnAHostNameAndRefusesAnEmptyOne)
{
  PoseStreamServerOptions options = anyFreePort();
  options.host = "localhost";
  PoseStreamServer server(options);
  server.publish(only(twoPoses()));
  EXPECT_EQ(receiveAll(server, 200).size(), 2u);
  options.host = "";
  EXPECT_EQ(fixtures::errorMessageOf([&] { PoseStreamServer refused(options); }),
    "'' is neither an IPv4 address nor a host name with one (empty)");
}

TEST(PoseStreamServer, RefusesNamesOpenIGTLinkWouldCutAndTimesThatDoNotMatchThePoses)
{
  for (const std::string name : { std::string(), std::string(21, 'c') })
  {
    PoseStreamServerOptions options = anyFreePort();
    options.cameraName = name;
    EXPECT_EQ(fixtures::errorMessageOf([&] { PoseStreamServer server(options); }),
      "the camera's device name '" + name + "' must have 1 to 20 characters (OpenIGTLink's limit)");
  }
  PoseStreamServerOptions options = anyFreePort();
  options.cameraNames = CameraDeviceNames::OnePerFrame;
  PoseStreamServer server(options);
  ServedPoses poses = threeFramesOfAVideo();
  poses.cameraToCT[2].frameId = 123456789;
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(poses); }),
    "pose server: refusing to publish: frame 123456789's device name VideoCamera_123456789 is "
    "longer than OpenIGTLink's 20 characters");
  poses = threeFramesOfAVideo();
  poses.frameTimesS.pop_back();
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(poses); }),
    "pose server: refusing to publish: 2 frame times for 3 poses: one finite time per pose, or "
    "none");
  poses.frameTimesS.push_back(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(poses); }),
    "pose server: refusing to publish: 3 frame times for 3 poses: one finite time per pose, or "
    "none");
}

TEST(PoseStreamServer, AFrameWithoutAPoseIsToldAsTrackingLostInItsPlaceInTheVideo)
{
  PoseStreamServer server(anyFreePort());
  ServedPoses poses = threeFramesOfAVideo();
  // Frames 10, 12 and 13 have poses; 11 (at 0.44 s) was not registered, nor was 14 (0.56 s).
  poses.cameraToCT[1].frameId = 12;
  poses.cameraToCT[2].frameId = 13;
  poses.frameTimesS = { 0.4, 0.48, 0.52 };
  poses.framesWithoutPose = { { 11, 0.44, "SfM did not register it" }, { 14, 0.56, "" } };
  server.publish(poses);
  const std::vector<WireMessage> got = receiveAll(server, 200);
  ASSERT_EQ(got.size(), 6u);
  const std::vector<std::string> types = { got[1].type, got[2].type, got[3].type, got[4].type,
    got[5].type };
  EXPECT_EQ(
    types, (std::vector<std::string>{ "TRANSFORM", "STATUS", "TRANSFORM", "TRANSFORM", "STATUS" }));
  for (size_t i = 1; i + 1 < got.size(); ++i)
  {
    EXPECT_NEAR(got[i + 1].timeS - got[i].timeS, 0.04, 1e-6) << i;
  }
  const WireMessage& lost = got[2];
  EXPECT_EQ(lost.device, "CameraToCT");
  EXPECT_EQ(bigEndian(lost.body, 0, 2), 16u); // STATUS_NOT_PRESENT
  EXPECT_EQ(bigEndian(lost.body, 2, 8), 11u);
  EXPECT_EQ(field(lost.body, 10, 20), "TrackingLost");
  EXPECT_EQ(
    field(lost.body, 30, lost.body.size() - 30), "frame 11 has no pose: SfM did not register it");
  EXPECT_EQ(field(got[5].body, 30, got[5].body.size() - 30), "frame 14 has no pose");

  // A lost frame needs a time when the poses have them.
  poses.framesWithoutPose[0].timeS = std::nan("");
  const std::string message = fixtures::errorMessageOf([&] { server.publish(poses); });
  EXPECT_EQ(message,
    "pose server: refusing to publish: frame 11 without a pose has no finite time, and the poses "
    "have times");
}

TEST(PoseStreamServer, EachPoseCanComeWithItsFramesPictureAsAnImageAtTheSameTime)
{
  PoseStreamServerOptions options = anyFreePort();
  options.imageName = "Endoscope";
  PoseStreamServer server(options);
  ServedPoses poses = threeFramesOfAVideo();
  for (int i = 0; i < 3; ++i)
  {
    FramePicture picture;
    picture.widthPx = 4;
    picture.heightPx = 2;
    for (int k = 0; k < 24; ++k)
    {
      picture.rgb.push_back(static_cast<unsigned char>(10 * i + k));
    }
    poses.pictures.push_back(picture);
  }
  server.publish(poses);
  const std::vector<WireMessage> got = receiveAll(server, 200);
  ASSERT_EQ(got.size(), 7u);
  for (size_t i = 0; i < 3; ++i)
  {
    const WireMessage& image = got[1 + 2 * i];
    const WireMessage& pose = got[2 + 2 * i];
    EXPECT_EQ(image.type, "IMAGE");
    EXPECT_EQ(image.device, "Endoscope");
    EXPECT_EQ(pose.type, "TRANSFORM");
    EXPECT_EQ(image.timeS, pose.timeS);
    // Body: version (2), components (1), scalar type (1), endian (1), coordinate (1),
    // size (3 x 2), matrix (12 x 4), subvolume offset and size (6 x 2), then the pixels.
    ASSERT_EQ(image.body.size(), 72u + 24u);
    EXPECT_EQ(bigEndian(image.body, 2, 1), 3u); // RGB
    EXPECT_EQ(bigEndian(image.body, 3, 1), 3u); // uint8
    EXPECT_EQ(bigEndian(image.body, 6, 2), 4u);
    EXPECT_EQ(bigEndian(image.body, 8, 2), 2u);
    EXPECT_EQ(static_cast<unsigned char>(image.body[72]), 10 * i);
    EXPECT_EQ(static_cast<unsigned char>(image.body[72 + 23]), 10 * i + 23);
  }

  poses.pictures.pop_back();
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(poses); }),
    "pose server: refusing to publish: 2 pictures for 3 poses: one per pose, or none");
  poses.pictures.push_back(poses.pictures.back());
  poses.pictures.back().rgb.pop_back();
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(poses); }),
    "pose server: refusing to publish: a picture of 4x2 px holds 23 bytes, not 3 per pixel");
}

TEST(PoseStreamServer, ADegradedPoseIsFollowedByATrackingDegradedStatusWithItsFrameId)
{
  PoseStreamServer server(anyFreePort());
  ServedPoses poses = threeFramesOfAVideo();
  poses.degradedPoses = { { 11, "features cast from a prediction" } };
  server.publish(poses);
  const std::vector<WireMessage> got = receiveAll(server, 200);
  ASSERT_EQ(got.size(), 5u);
  EXPECT_EQ(got[2].type, "TRANSFORM");
  const WireMessage& status = got[3];
  EXPECT_EQ(status.type, "STATUS");
  EXPECT_EQ(status.device, "CameraToCT");
  EXPECT_EQ(status.timeS, got[2].timeS);
  EXPECT_EQ(bigEndian(status.body, 0, 2), 2u);
  EXPECT_EQ(bigEndian(status.body, 2, 8), 11u);
  EXPECT_EQ(field(status.body, 10, 20), "TrackingDegraded");
  EXPECT_EQ(field(status.body, 30, status.body.size() - 30),
    "frame 11's pose is degraded: features cast from a prediction");
  EXPECT_EQ(got[4].type, "TRANSFORM");

  poses.degradedPoses = { { 13, "" } };
  EXPECT_EQ(fixtures::errorMessageOf([&] { server.publish(poses); }),
    "pose server: refusing to publish: frame 13 is said to be degraded but has no pose among "
    "those published");
}

TEST(LivePoseStream, AConnectedClientGetsEachFrameInOrderWithIncreasingTimesAndTheLostStretch)
{
  PoseStreamServerOptions options = anyFreePort();
  options.cameraName = "Endoscope";
  LivePoseStream stream(options, "test");
  const int fd = connectTo(stream.port());
  ASSERT_TRUE(stream.waitForClient(5.0));
  // Frames 0-2 tracked, 3-4 lost, 5 degraded, 6 tracked.
  for (int id = 0; id < 7; ++id)
  {
    FramePose pose;
    pose.frameId = id;
    pose.cameraToWorld.centre = Eigen::Vector3d(100.0 + id, 90.0, 30.0);
    if (id == 3 || id == 4)
    {
      stream.sendLost(id, "too few features");
    }
    else
    {
      stream.sendPose(pose, id == 5 ? "features cast from a prediction" : "");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(stream.finish(5.0));
  const std::vector<WireMessage> got = messagesArrivedOn(fd);
  const std::vector<std::pair<std::string, std::string>> expected = { { "TRANSFORM", "" },
    { "TRANSFORM", "" }, { "TRANSFORM", "" }, { "STATUS", "TrackingLost" },
    { "STATUS", "TrackingLost" }, { "TRANSFORM", "" }, { "STATUS", "TrackingDegraded" },
    { "TRANSFORM", "" } };
  ASSERT_EQ(got.size(), expected.size());
  for (size_t i = 0; i < got.size(); ++i)
  {
    EXPECT_EQ(got[i].type, expected[i].first) << i;
    EXPECT_EQ(got[i].device, "Endoscope") << i;
    if (got[i].type == "STATUS")
    {
      EXPECT_EQ(field(got[i].body, 10, 20), expected[i].second) << i;
    }
    // A degraded frame's STATUS shares its pose's time; every new frame is later.
    if (i > 0)
    {
      EXPECT_GE(got[i].timeS, got[i - 1].timeS) << i;
      EXPECT_TRUE(expected[i].second == "TrackingDegraded" || got[i].timeS > got[i - 1].timeS) << i;
    }
  }
  EXPECT_EQ(bigEndian(got[3].body, 2, 8), 3u);
  EXPECT_EQ(bigEndian(got[4].body, 2, 8), 4u);
}

TEST(LivePoseStream, NoClientWithinTheWaitIsToldAndTheStreamFinishesAtOnce)
{
  LivePoseStream stream(anyFreePort(), "test");
  const auto before = std::chrono::steady_clock::now();
  EXPECT_FALSE(stream.waitForClient(0.2));
  EXPECT_GE(std::chrono::steady_clock::now() - before, std::chrono::milliseconds(200));
  FramePose pose;
  stream.sendPose(pose);
  EXPECT_TRUE(stream.finish(5.0));
}
