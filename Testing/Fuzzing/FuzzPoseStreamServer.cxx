// Fuzzes what `vimlop serve` does with the bytes a client sends: a client
// connects over loopback, sends the input (garbage, partial or well-formed
// OpenIGTLink messages such as GET_TRANSFORM), closes its sending side and
// reads. The server must neither crash nor stall, must close the connection,
// and must have sent exactly the published TRANSFORM messages, each with a
// valid OpenIGTLink header and CRC.
#include <vimlop/Core/Error.h>
#include <vimlop/Server/PoseStreamServer.h>

#include <igtlMessageHeader.h>
#include <igtlStatusMessage.h>
#include <igtlTransformMessage.h>
#include <igtl_header.h>

#include <arpa/inet.h>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace
{

std::unique_ptr<vimlop::PoseStreamServer> server;
/// CTFromSfM, two camera poses and the verdict.
constexpr int publishedMessages = 4;

/// Counts the TRANSFORM and STATUS messages in `bytes` whose header and body
/// unpack with a valid CRC; -1 when anything else is there.
int validMessages(const std::string& bytes)
{
  int count = 0;
  size_t at = 0;
  while (at + IGTL_HEADER_SIZE <= bytes.size())
  {
    igtl::MessageHeader::Pointer header = igtl::MessageHeader::New();
    header->InitPack();
    std::memcpy(header->GetPackPointer(), bytes.data() + at, IGTL_HEADER_SIZE);
    header->Unpack();
    const size_t body = header->GetBodySizeToRead();
    const bool transform = std::strcmp(header->GetDeviceType(), "TRANSFORM") == 0;
    if ((!transform && std::strcmp(header->GetDeviceType(), "STATUS") != 0) ||
      at + IGTL_HEADER_SIZE + body > bytes.size())
    {
      return -1;
    }
    igtl::MessageBase::Pointer message;
    if (transform)
    {
      message = igtl::TransformMessage::New();
    }
    else
    {
      message = igtl::StatusMessage::New();
    }
    message->SetMessageHeader(header);
    message->AllocatePack();
    std::memcpy(message->GetPackBodyPointer(), bytes.data() + at + IGTL_HEADER_SIZE, body);
    if (!(message->Unpack(1) & igtl::MessageHeader::UNPACK_BODY))
    {
      return -1;
    }
    ++count;
    at += IGTL_HEADER_SIZE + body;
  }
  return at == bytes.size() ? count : -1;
}

/// Fails the input with what went wrong on the harness's side of the socket.
[[noreturn]] void harnessFailure(const char* what, int error)
{
  std::fprintf(stderr, "fuzz server harness: %s: %s\n", what, std::strerror(error));
  std::abort();
}

/// A loopback client of the server. libFuzzer's timers interrupt system
/// calls (EINTR): an interrupted connect() goes on in the background and is
/// awaited. At over ten thousand inputs a second the client's closed
/// connections wait in TIME_WAIT and can use up the loopback port pairs
/// (EADDRNOTAVAIL): a limit of the harness, retried for a while. Any other
/// failure to connect (the server's listening socket gone) is a finding.
int connectToServer()
{
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(server->port()));
  inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  for (int attempt = 0; attempt < 1000; ++attempt)
  {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0)
    {
      harnessFailure("socket", errno);
    }
    int error =
      connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0 ? 0 : errno;
    if (error == EINTR)
    {
      pollfd pending{ fd, POLLOUT, 0 };
      while (poll(&pending, 1, -1) < 0 && errno == EINTR)
      {
      }
      socklen_t length = sizeof(error);
      getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length);
    }
    if (error == 0)
    {
      return fd;
    }
    close(fd);
    if (error != EADDRNOTAVAIL)
    {
      harnessFailure("connect to the server", error);
    }
    usleep(10000);
  }
  harnessFailure("connect to the server", EADDRNOTAVAIL);
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  vimlop::PoseStreamServerOptions options;
  options.port = 0;
  server = std::make_unique<vimlop::PoseStreamServer>(options);
  vimlop::SimilarityTransform ctFromSfm;
  ctFromSfm.scale = 2.0;
  ctFromSfm.translation = Eigen::Vector3d(1.0, 2.0, 3.0);
  std::vector<vimlop::FramePose> poses(2);
  poses[1].frameId = 12;
  poses[1].cameraToWorld.centre = Eigen::Vector3d(-4.0, 5.0, 6.0);
  vimlop::ServedPoses served;
  served.ctFromSfm = ctFromSfm;
  served.cameraToCT = poses;
  served.frameTimesS = { 0.0, 0.4 };
  served.verdict = vimlop::PoseVerdict{ false, "contour error 2.0 px" };
  server->publish(served);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size > 65536)
  {
    return 0; // more than the loopback socket buffers hold before the server reads
  }
  const int fd = connectToServer();
  size_t sent = 0;
  while (sent < size)
  {
    const ssize_t n = send(fd, data + sent, size - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      harnessFailure("send", errno);
    }
    sent += static_cast<size_t>(n);
  }
  shutdown(fd, SHUT_WR);

  // Serve until the server has accepted the client and closed it again.
  bool accepted = false;
  int rounds = 0;
  server->serve(
    [&]
    {
      accepted = accepted || server->clientCount() > 0;
      return ++rounds < 200 && !(accepted && server->clientCount() == 0);
    });
  if (!accepted || server->clientCount() != 0)
  {
    std::abort(); // the server stalled on this input or kept a finished client
  }
  std::string received;
  char buffer[4096];
  for (;;)
  {
    const ssize_t got = recv(fd, buffer, sizeof(buffer), 0);
    if (got < 0 && errno == EINTR)
    {
      continue;
    }
    if (got <= 0)
    {
      break;
    }
    received.append(buffer, static_cast<size_t>(got));
  }
  close(fd);
  if (validMessages(received) != publishedMessages)
  {
    std::abort();
  }
  return 0;
}
