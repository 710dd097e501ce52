// A navigation-software stand-in for `vimlop serve`: an OpenIGTLink receiver
// written against the OpenIGTLink library's client side (not VIMLOP's code).
// It starts the server, harasses it with hostile clients (garbage bytes, early
// disconnects, more connections than it serves), then, beside 500 idle
// connections from 8 addresses, receives every message as a well-behaved client and checks
// them against the pose file or the result folder's result.json: the devices in the order of
// the video (one moving camera, or one per frame with --per-frame-names), the matrices (in RAS,
// as the protocol wants), the timestamps (the frames' times apart, none in the future) and the
// STATUS verdict; finally it stops the server with SIGINT.
//
// Usage: TestPoseReceiver <vimlop> --poses <poses.json> [serve flags...]
//        TestPoseReceiver <vimlop> --result <result folder> [serve flags...]
//        TestPoseReceiver <vimlop> --track <out folder> [track flags...]
// The last follows `vimlop track --serve` live instead (followTracking()).

#include <igtlClientSocket.h>
#include <igtlImageMessage.h>
#include <igtlMessageHeader.h>
#include <igtlStatusMessage.h>
#include <igtlTransformMessage.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <arpa/inet.h>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <netinet/in.h>
#include <optional>
#include <random>
#include <string>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace
{

int failures = 0;

void check(bool ok, const std::string& what)
{
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what.c_str());
  failures += ok ? 0 : 1;
}

/// Connects from `from` (an address of the loopback block 127/8).
int rawConnect(int port, const std::string& from = "127.0.0.1")
{
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in source{};
  source.sin_family = AF_INET;
  inet_pton(AF_INET, from.c_str(), &source.sin_addr);
  if (bind(fd, reinterpret_cast<sockaddr*>(&source), sizeof(source)) != 0)
  {
    close(fd);
    return -1;
  }
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0)
  {
    close(fd);
    return -1;
  }
  return fd;
}

/// One message as received: its header, and the matrix of a TRANSFORM or the
/// code, error name and text of a STATUS.
struct Received
{
  std::string type;
  std::string device;
  double timeS = 0.0;
  std::vector<float> matrix;
  int code = 0;
  std::uint64_t subCode = 0;
  std::string errorName;
  std::string text;
  /// An IMAGE's size and components.
  int width = 0;
  int height = 0;
  int components = 0;
};

/// Receives messages until `expected` arrived, the server closed the
/// connection or `seconds` passed.
std::vector<Received> receiveMessages(int port, size_t expected, int seconds = 10)
{
  std::vector<Received> got;
  igtl::ClientSocket::Pointer socket = igtl::ClientSocket::New();
  if (socket->ConnectToServer("127.0.0.1", port) != 0)
  {
    return got;
  }
  socket->SetReceiveTimeout(10000);
  const auto start = std::chrono::steady_clock::now();
  while (got.size() < expected &&
    std::chrono::steady_clock::now() - start < std::chrono::seconds(seconds))
  {
    igtl::MessageHeader::Pointer header = igtl::MessageHeader::New();
    header->InitPack();
    if (socket->Receive(header->GetPackPointer(), header->GetPackSize()) != header->GetPackSize())
    {
      break;
    }
    header->Unpack();
    Received r;
    r.type = header->GetDeviceType();
    r.device = header->GetDeviceName();
    igtl::TimeStamp::Pointer stamp = igtl::TimeStamp::New();
    header->GetTimeStamp(stamp);
    r.timeS = stamp->GetTimeStamp();
    igtl::MessageBase::Pointer body;
    igtl::TransformMessage::Pointer transform = igtl::TransformMessage::New();
    igtl::StatusMessage::Pointer status = igtl::StatusMessage::New();
    igtl::ImageMessage::Pointer image = igtl::ImageMessage::New();
    if (r.type == "TRANSFORM")
    {
      body = transform;
    }
    else if (r.type == "IMAGE")
    {
      body = image;
    }
    else if (r.type == "STATUS")
    {
      body = status;
    }
    else
    {
      socket->Skip(header->GetBodySizeToRead(), 0);
      got.push_back(r);
      continue;
    }
    body->SetMessageHeader(header);
    body->AllocatePack();
    socket->Receive(body->GetPackBodyPointer(), body->GetPackBodySize());
    if (!(body->Unpack(1) & igtl::MessageHeader::UNPACK_BODY))
    {
      break; // CRC mismatch
    }
    if (r.type == "TRANSFORM")
    {
      igtl::Matrix4x4 m;
      transform->GetMatrix(m);
      for (int i = 0; i < 4; ++i)
      {
        for (int j = 0; j < 4; ++j)
        {
          r.matrix.push_back(m[i][j]);
        }
      }
    }
    else if (r.type == "IMAGE")
    {
      int size[3];
      image->GetDimensions(size);
      r.width = size[0];
      r.height = size[1];
      r.components = image->GetNumComponents();
    }
    else
    {
      r.code = status->GetCode();
      r.subCode = status->GetSubCode();
      r.errorName = status->GetErrorName();
      r.text = status->GetStatusString();
    }
    got.push_back(r);
  }
  socket->CloseSocket();
  return got;
}

using Matrix = std::array<double, 16>;

/// A 4 x 4 matrix from JSON: 16 numbers row-major, or 4 rows of 4.
Matrix toMatrix(const nlohmann::json& value)
{
  Matrix m{};
  for (int i = 0; i < 16; ++i)
  {
    m[static_cast<size_t>(i)] =
      value.size() == 16 ? value[i].get<double>() : value[i / 4][i % 4].get<double>();
  }
  return m;
}

/// A transform into the LPS CT frame re-expressed into RAS: the first two rows change sign.
Matrix intoRas(Matrix m)
{
  for (size_t i = 0; i < 8; ++i)
  {
    m[i] = -m[i];
  }
  return m;
}

/// The largest difference between a matrix sent and one received, relative
/// to each element's size: floats on the wire, translations up to 10^3 mm.
double worstRelativeError(const Matrix& sent, const std::vector<float>& received)
{
  double worst = 0.0;
  for (size_t i = 0; i < 16; ++i)
  {
    worst = std::max(worst, std::abs(sent[i] - received[i]) / std::max(1.0, std::abs(sent[i])));
  }
  return worst;
}

double determinant3(const std::vector<float>& m)
{
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
    m[2] * (m[4] * m[9] - m[5] * m[8]);
}

/// Starts `args` (the vimlop program first) with its stdout read here until
/// it announces `127.0.0.1:<port>`; returns its process id, or -1 after
/// killing it when it announced none.
pid_t launch(std::vector<std::string> args, int& port)
{
  int out[2];
  if (pipe(out) != 0)
  {
    return -1;
  }
  const pid_t child = fork();
  if (child == 0)
  {
    dup2(out[1], STDOUT_FILENO);
    close(out[0]);
    std::vector<char*> pointers;
    for (std::string& arg : args)
    {
      pointers.push_back(arg.data());
    }
    pointers.push_back(nullptr);
    execv(pointers[0], pointers.data());
    _exit(127);
  }
  close(out[1]);
  char line[512] = {};
  FILE* stream = fdopen(out[0], "r");
  if (!std::fgets(line, sizeof(line), stream) || !std::strstr(line, "127.0.0.1:") ||
    std::sscanf(std::strstr(line, "127.0.0.1:") + 10, "%d", &port) != 1)
  {
    std::fprintf(stderr, "the server did not announce its port: %s\n", line);
    kill(child, SIGKILL);
    return -1;
  }
  // The rest of its output goes on to ours, so that the pipe never fills.
  std::thread(
    [stream]
    {
      char rest[512];
      while (std::fgets(rest, sizeof(rest), stream))
      {
        std::fputs(rest, stdout);
      }
      std::fclose(stream);
    })
    .detach();
  return child;
}

/// Waits up to `seconds` for `child` to end; its exit code, or -1 (killed) when it did not.
int exitCodeOf(pid_t child, int seconds)
{
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  pid_t done = 0;
  while ((done = waitpid(child, &status, WNOHANG)) == 0 &&
    std::chrono::steady_clock::now() - start < std::chrono::seconds(seconds))
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (done != child)
  {
    kill(child, SIGKILL);
    waitpid(child, &status, 0);
    return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

/// What one message must carry, from the files themselves (not VIMLOP's readers).
struct Expected
{
  std::string type;
  std::string device;
  Matrix matrix{};
  /// The frame's time on the video's clock (result.json's time_s), when known.
  std::optional<double> frameTimeS;
  int code = 0;
  std::string errorName;
  int width = 0;
  int height = 0;
  /// The frame a live stream's message is for (`--track`).
  int frameId = -1;
};

Expected transformOf(const std::string& device, const Matrix& matrix)
{
  Expected e;
  e.type = "TRANSFORM";
  e.device = device;
  e.matrix = matrix;
  return e;
}

/// `vimlop track --serve` followed live: the client connects before the
/// first frame (--wait-for-client-s) and must receive, frame after frame as
/// tracking.json lists them, a TRANSFORM of the moving camera for each frame
/// that is not lost (its pose as in tracked-poses.json, in RAS), followed by
/// a STATUS TrackingDegraded for a degraded one, and a STATUS TrackingLost
/// for each lost one, each frame stamped later than the one before.
int followTracking(
  const std::string& vimlop, const std::string& out, const std::vector<std::string>& trackArgs)
{
  std::vector<std::string> args = { vimlop, "track", "--serve", "--port", "0",
    "--wait-for-client-s", "60", "--out", out };
  args.insert(args.end(), trackArgs.begin(), trackArgs.end());
  int port = 0;
  const pid_t tracker = launch(args, port);
  if (tracker < 0)
  {
    return 1;
  }
  const std::vector<Received> got = receiveMessages(port, SIZE_MAX, 120);
  check(exitCodeOf(tracker, 60) == 0, "vimlop track ends with 0");
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(out + "/tracking.json"));
  const nlohmann::json poses =
    nlohmann::json::parse(std::ifstream(out + "/tracked-poses.json"))["poses"];
  std::vector<Expected> expected;
  std::vector<int> frameOf; // the index in per_frame of each expected message
  int counts[3] = { 0, 0, 0 };
  size_t pose = 0;
  for (const auto& frame : report["per_frame"])
  {
    const int id = frame["frame_id"].get<int>();
    const std::string state = frame["state"].get<std::string>();
    counts[state == "tracking" ? 0 : state == "degraded" ? 1 : 2]++;
    if (state == "lost")
    {
      expected.push_back(
        { "STATUS", "CameraToCT", {}, std::nullopt, 16, "TrackingLost", 0, 0, id });
    }
    else
    {
      check(pose < poses.size() && poses[pose]["frame_id"].get<int>() == id,
        "frame " + std::to_string(id) + " has its pose in tracked-poses.json");
      expected.push_back(transformOf(
        "CameraToCT", intoRas(toMatrix(poses[std::min(pose, poses.size() - 1)]["camera_to_ct"]))));
      expected.back().frameId = id;
      ++pose;
      if (state == "degraded")
      {
        expected.push_back(
          { "STATUS", "CameraToCT", {}, std::nullopt, 2, "TrackingDegraded", 0, 0, id });
      }
    }
  }
  std::printf("%d tracking, %d degraded, %d lost frames: expecting %zu messages\n", counts[0],
    counts[1], counts[2], expected.size());
  // The sequence must have all three, or this test would not test the stream's statuses.
  check(counts[0] > 0 && counts[1] > 0 && counts[2] > 0, "the frames have all three states");
  check(got.size() == expected.size(),
    "received " + std::to_string(got.size()) + " of " + std::to_string(expected.size()) +
      " messages");
  double previousS = 0.0;
  for (size_t k = 0; k < std::min(got.size(), expected.size()); ++k)
  {
    const Expected& e = expected[k];
    const Received& r = got[k];
    const int id = e.frameId;
    const std::string what = "message " + std::to_string(k) + " (frame " + std::to_string(id) +
      ", " + e.type + " " + e.errorName + ")";
    if (r.type != e.type || r.device != e.device)
    {
      check(false, what + " received as " + r.type + " " + r.device);
      continue;
    }
    if (e.errorName == "TrackingDegraded")
    {
      // It follows its frame's pose, at the same time.
      check(r.timeS == previousS, what + " carries its pose's time");
    }
    else
    {
      check(r.timeS > previousS, what + " is stamped later than the frame before it");
    }
    previousS = r.timeS;
    if (e.type == "STATUS")
    {
      check(r.code == e.code && r.errorName == e.errorName && r.subCode == std::uint64_t(id),
        what + " says code " + std::to_string(r.code) + " '" + r.errorName + "', sub-code " +
          std::to_string(r.subCode) + ": " + r.text);
      continue;
    }
    const double worst = worstRelativeError(e.matrix, r.matrix);
    check(worst < 1e-5,
      what + " is the tracked pose in RAS (worst relative element error " + std::to_string(worst) +
        ")");
  }
  return failures == 0 ? 0 : 1;
}

int main(int argc, char** argv)
{
  const std::string mode = argc >= 4 ? argv[2] : "";
  std::signal(SIGPIPE, SIG_IGN);
  if (mode == "--track")
  {
    return followTracking(argv[1], argv[3], std::vector<std::string>(argv + 4, argv + argc));
  }
  if (mode != "--poses" && mode != "--result")
  {
    std::fprintf(stderr,
      "usage: %s <vimlop> --poses <poses.json> | --result <result folder> [serve flags...]\n"
      "       %s <vimlop> --track <out folder> [track flags...]\n",
      argv[0], argv[0]);
    return 2;
  }
  std::vector<std::string> serveFlags(argv + 4, argv + argc);
  const bool perFrame =
    std::find(serveFlags.begin(), serveFlags.end(), "--per-frame-names") != serveFlags.end();
  const auto named = std::find(serveFlags.begin(), serveFlags.end(), "--camera-name");
  const std::string camera =
    named != serveFlags.end() && named + 1 != serveFlags.end() ? *(named + 1) : "CameraToCT";
  const bool images =
    std::find(serveFlags.begin(), serveFlags.end(), "--images") != serveFlags.end();
  const auto cameraDevice = [perFrame, &camera](int frameId)
  { return perFrame ? "VideoCamera_" + std::to_string(frameId) : camera; };
  std::vector<Expected> expected;
  double expectedScale = 0.0;
  if (mode == "--poses")
  {
    const nlohmann::json poses = nlohmann::json::parse(std::ifstream(argv[3]));
    for (const auto& pose : poses["poses"])
    {
      expected.push_back(transformOf(
        cameraDevice(pose["frame_id"].get<int>()), intoRas(toMatrix(pose["camera_to_ct"]))));
    }
  }
  else
  {
    const nlohmann::json result =
      nlohmann::json::parse(std::ifstream(std::string(argv[3]) + "/result.json"));
    expected.push_back(transformOf("CTFromSfM", intoRas(toMatrix(result["transform"]["matrix"]))));
    expectedScale = result["transform"]["scale"].get<double>();
    for (const auto& frame : result["frames"])
    {
      Expected e =
        transformOf(cameraDevice(frame["id"].get<int>()), intoRas(toMatrix(frame["camera_to_ct"])));
      if (frame.contains("time_s"))
      {
        e.frameTimeS = frame["time_s"].get<double>();
      }
      if (images)
      {
        // The frame's picture first, at the same time.
        Expected picture;
        picture.type = "IMAGE";
        picture.device = "CameraImage";
        picture.frameTimeS = e.frameTimeS;
        picture.width = frame["intrinsics"]["width_px"].get<int>();
        picture.height = frame["intrinsics"]["height_px"].get<int>();
        expected.push_back(picture);
      }
      expected.push_back(e);
    }
    // A frame without a pose is a TrackingLost STATUS in its place in the video.
    for (const auto& frame : result.value("frames_without_pose", nlohmann::json::array()))
    {
      Expected e{ "STATUS", camera, {}, std::nullopt, 16, "TrackingLost" };
      if (frame["time_s"].is_number())
      {
        e.frameTimeS = frame["time_s"].get<double>();
      }
      expected.push_back(e);
    }
    if (std::all_of(expected.begin() + 1, expected.end(),
          [](const Expected& e) { return e.frameTimeS.has_value(); }))
    {
      std::stable_sort(expected.begin() + 1, expected.end(),
        [](const Expected& a, const Expected& b) { return *a.frameTimeS < *b.frameTimeS; });
    }
    if (result.contains("confidence"))
    {
      const bool failure = result["confidence"]["failure"].get<bool>();
      expected.push_back({ "STATUS", camera, {}, std::nullopt, failure ? 2 : 1,
        failure ? "RegistrationFlagged" : "" });
    }
  }
  std::printf("expecting %zu messages\n", expected.size());

  std::vector<std::string> args = { argv[1], "serve", argv[2], argv[3], "--port", "0",
    "--duration-s", "120" };
  args.insert(args.end(), serveFlags.begin(), serveFlags.end());
  int port = 0;
  const pid_t server = launch(args, port);
  if (server < 0)
  {
    return 1;
  }
  std::printf("server on port %d\n", port);

  // Garbage: a client that sends 64 KiB of random bytes and stays connected.
  const int garbage = rawConnect(port);
  std::mt19937 rng(1);
  std::vector<char> noise(1 << 16);
  for (char& c : noise)
  {
    c = static_cast<char>(rng());
  }
  check(garbage >= 0 && send(garbage, noise.data(), noise.size(), MSG_NOSIGNAL) > 0,
    "garbage client connected and sent");

  // Early disconnects.
  for (int i = 0; i < 20; ++i)
  {
    const int fd = rawConnect(port);
    if (fd >= 0)
    {
      close(fd);
    }
  }
  // More connections than the server serves at once (512 by default), never
  // read from, from `hosts` addresses (127.0.0.10, ...: the server keeps 64
  // per address).
  const auto openCrowd = [port](int count, int hosts)
  {
    std::vector<int> crowd;
    for (int i = 0; i < count; ++i)
    {
      crowd.push_back(rawConnect(port, "127.0.0." + std::to_string(10 + i % hosts)));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    return crowd;
  };
  const auto closeCrowd = [](const std::vector<int>& crowd)
  {
    for (int fd : crowd)
    {
      if (fd >= 0)
      {
        close(fd);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  };
  closeCrowd(openCrowd(520, 9));
  // 500 idle connections from 8 hosts stay open while the well-behaved clients come.
  const std::vector<int> idle = openCrowd(500, 8);
  check(std::count(idle.begin(), idle.end(), -1) == 0, "500 idle connections open");

  // A well-behaved client receives every message in order: the poses in RAS
  // stamped with their frames' times, then the verdict.
  const std::vector<Received> got = receiveMessages(port, expected.size());
  const double receivedS =
    std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  check(got.size() == expected.size(),
    "received " + std::to_string(got.size()) + " of " + std::to_string(expected.size()) +
      " messages");
  std::optional<Received> firstCamera;
  std::optional<Expected> firstExpected;
  double previousS = 0.0;
  for (size_t k = 0; k < std::min(got.size(), expected.size()); ++k)
  {
    const Expected& e = expected[k];
    const Received& r = got[k];
    const std::string what = "message " + std::to_string(k) + " (" + e.type + " " + e.device + ")";
    if (r.type != e.type || r.device != e.device)
    {
      check(false, what + " received, not " + r.type + " " + r.device);
      continue;
    }
    check(r.timeS <= receivedS && r.timeS > receivedS - 300.0,
      what + " stamped within the server's life, not in the future");
    if (e.type == "STATUS")
    {
      check(r.code == e.code && r.errorName == e.errorName,
        what + " says code " + std::to_string(r.code) + " '" + r.errorName + "': " + r.text);
      continue;
    }
    if (e.type == "IMAGE")
    {
      check(r.width == e.width && r.height == e.height && r.components == 3,
        what + " is the frame's RGB picture (" + std::to_string(r.width) + "x" +
          std::to_string(r.height) + ", " + std::to_string(r.components) + " components)");
      check(k + 1 < got.size() && got[k + 1].timeS == r.timeS,
        what + " carries the time of the pose after it");
      continue;
    }
    const double worst = worstRelativeError(e.matrix, r.matrix);
    check(worst < 1e-5,
      what + " matches in RAS (worst relative element error " + std::to_string(worst) + ")");
    if (e.device == "CTFromSfM")
    {
      continue;
    }
    check(r.timeS >= previousS, what + " is not stamped before the frame before it");
    previousS = r.timeS;
    if (!firstCamera)
    {
      firstCamera = r;
      firstExpected = e;
    }
    else if (e.frameTimeS && firstExpected->frameTimeS)
    {
      const double apartS = *e.frameTimeS - *firstExpected->frameTimeS;
      check(std::abs((r.timeS - firstCamera->timeS) - apartS) < 1e-3,
        what + " stamped " + std::to_string(apartS) + " s after the first frame, as the video");
    }
  }
  if (expectedScale > 0.0 && !got.empty() && got[0].device == "CTFromSfM")
  {
    // The similarity keeps its scale in the 3 x 3 block: the cube root of its determinant.
    const double scale = std::cbrt(determinant3(got[0].matrix));
    check(std::abs(scale - expectedScale) < 1e-5 * expectedScale,
      "CTFromSfM carries the scale " + std::to_string(scale) +
        " (result.json: " + std::to_string(expectedScale) + ")");
  }
  // The garbage client is still connected and the server still alive.
  check(kill(server, 0) == 0, "server alive after the hostile clients");
  if (garbage >= 0)
  {
    close(garbage);
  }
  // A second well-behaved client is served too.
  const std::vector<Received> again = receiveMessages(port, expected.size());
  bool same = again.size() == got.size();
  for (size_t k = 0; same && k < got.size(); ++k)
  {
    same = again[k].device == got[k].device && again[k].matrix == got[k].matrix &&
      again[k].timeS == got[k].timeS;
  }
  check(same, "a second client receives the same messages");
  // None of the idle connections was closed to serve the clients.
  int closed = 0;
  for (int fd : idle)
  {
    char buffer[4096];
    ssize_t n = 0;
    while ((n = recv(fd, buffer, sizeof(buffer), MSG_DONTWAIT)) > 0)
    {
    }
    closed += n == 0 ? 1 : 0;
  }
  check(closed == 0, std::to_string(closed) + " of the 500 idle connections closed by the server");
  closeCrowd(idle);

  kill(server, SIGINT);
  check(exitCodeOf(server, 5) == 0, "server stops cleanly on SIGINT");
  return failures == 0 ? 0 : 1;
}
