#include <vimlop/Server/PoseStreamServer.h>

#include <vimlop/Core/CoordinateFrames.h>
#include <vimlop/Core/Error.h>

#include "OpenIGTLinkMessages.h"

#include <algorithm>
#include <arpa/inet.h>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

namespace vimlop
{

using igtlmessages::packImage;
using igtlmessages::packStatus;
using igtlmessages::packTrackingDegraded;
using igtlmessages::packTrackingLost;
using igtlmessages::packTransform;

namespace
{

void setNonBlocking(int fd)
{
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL, 0) | O_NONBLOCK);
}

/// OpenIGTLink's device names are at most 20 bytes: a longer one is cut on the wire.
constexpr size_t maxDeviceNameLength = 20;

/// The IPv4 address of `host`: a dotted address, or a name (e.g. localhost) resolved.
in_addr resolveHost(const std::string& host)
{
  in_addr address{};
  if (inet_pton(AF_INET, host.c_str(), &address) == 1)
  {
    return address;
  }
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int status = host.empty() ? EAI_NONAME : getaddrinfo(host.c_str(), nullptr, &hints, &found);
  if (status != 0 || !found)
  {
    throw Error("'" + host + "' is neither an IPv4 address nor a host name with one (" +
      (host.empty() ? std::string("empty") : gai_strerror(status)) + ")");
  }
  address = reinterpret_cast<const sockaddr_in*>(found->ai_addr)->sin_addr;
  freeaddrinfo(found);
  return address;
}

std::string deviceNameOf(const PoseStreamServerOptions& options, int frameId)
{
  if (options.cameraNames == CameraDeviceNames::OneMovingCamera)
  {
    return options.cameraName;
  }
  return "VideoCamera_" + std::to_string(frameId);
}

std::string addressText(std::uint32_t address);

} // namespace

/// "10.1.2.3" or "10.1.0.0/16".
PoseStreamServer::AddressBlock PoseStreamServer::parseAddressBlock(const std::string& text)
{
  const auto slash = text.find('/');
  const std::string address = text.substr(0, slash);
  PoseStreamServer::AddressBlock block;
  in_addr parsed{};
  bool valid = inet_pton(AF_INET, address.c_str(), &parsed) == 1;
  if (valid && slash != std::string::npos)
  {
    const std::string bits = text.substr(slash + 1);
    valid = !bits.empty() && bits.size() <= 2 &&
      bits.find_first_not_of("0123456789") == std::string::npos && std::stoi(bits) <= 32;
    block.prefixBits = valid ? std::stoi(bits) : 0;
  }
  if (!valid)
  {
    throw Error("'" + text +
      "' is not an IPv4 address or block to allow (a.b.c.d, or a.b.c.d/n with n at most 32)");
  }
  block.address = parsed.s_addr;
  return block;
}

namespace
{

std::string addressText(std::uint32_t address)
{
  char text[INET_ADDRSTRLEN] = {};
  in_addr a{};
  a.s_addr = address;
  inet_ntop(AF_INET, &a, text, sizeof(text));
  return text;
}

} // namespace

PoseStreamServerOptions withNoticesOnStderr(
  PoseStreamServerOptions options, const std::string& label)
{
  options.onNotice = [label](const std::string& text)
  { std::fprintf(stderr, "%s: warning: %s\n", label.c_str(), text.c_str()); };
  return options;
}

PoseStreamServer::PoseStreamServer(const PoseStreamServerOptions& options)
  : Options(options)
{
  if (options.cameraName.empty() || options.cameraName.size() > maxDeviceNameLength)
  {
    throw Error("the camera's device name '" + options.cameraName + "' must have 1 to " +
      std::to_string(maxDeviceNameLength) + " characters (OpenIGTLink's limit)");
  }
  const in_addr address = resolveHost(options.host);
  const bool loopback = (ntohl(address.s_addr) >> 24) == 127;
  if (!loopback && !options.allowRemote)
  {
    throw Error("refusing to listen on " + options.host +
      ": not a loopback address (pass --allow-remote to serve other machines)");
  }
  if (options.port < 0 || options.port > 65535 || options.maxClients < 1 ||
    options.maxClientsPerAddress < 1 || !(options.stallTimeoutS > 0.0))
  {
    throw Error("the port must lie in [0, 65535], at least one client (and one per address) "
                "must be allowed and the stall timeout must be positive");
  }
  for (const std::string& text : options.allowedClients)
  {
    this->Allowed.push_back(parseAddressBlock(text));
  }
  // One descriptor per client, and a few for the rest of the process.
  rlimit files{};
  const rlim_t needed = static_cast<rlim_t>(options.maxClients) + 64;
  if (getrlimit(RLIMIT_NOFILE, &files) == 0 && files.rlim_cur < needed)
  {
    files.rlim_cur = std::min(needed, files.rlim_max);
    setrlimit(RLIMIT_NOFILE, &files);
    if (files.rlim_cur < needed)
    {
      throw Error("serving " + std::to_string(options.maxClients) + " clients needs " +
        std::to_string(needed) + " file descriptors; this process may open " +
        std::to_string(files.rlim_max) + " (ulimit -n): lower --max-clients");
    }
  }
  this->Listener = socket(AF_INET, SOCK_STREAM, 0);
  if (this->Listener < 0)
  {
    throw Error(std::string("cannot create a socket: ") + std::strerror(errno));
  }
  const int yes = 1;
  setsockopt(this->Listener, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  sockaddr_in bound{};
  bound.sin_family = AF_INET;
  bound.sin_addr = address;
  bound.sin_port = htons(static_cast<uint16_t>(options.port));
  if (bind(this->Listener, reinterpret_cast<sockaddr*>(&bound), sizeof(bound)) != 0 ||
    listen(this->Listener, 64) != 0)
  {
    const std::string reason = std::strerror(errno);
    close(this->Listener);
    throw Error(
      "cannot listen on " + options.host + ":" + std::to_string(options.port) + ": " + reason);
  }
  socklen_t length = sizeof(bound);
  getsockname(this->Listener, reinterpret_cast<sockaddr*>(&bound), &length);
  this->Port = ntohs(bound.sin_port);
  setNonBlocking(this->Listener);
}

PoseStreamServer::~PoseStreamServer()
{
  for (const Client& client : this->Clients)
  {
    close(client.fd);
  }
  if (this->Listener >= 0)
  {
    close(this->Listener);
  }
}

void PoseStreamServer::publish(const ServedPoses& poses)
{
  // Refused at the source: the float matrices of the protocol would carry an
  // overflow as -inf, a repeated id as two poses of one device, and a cut
  // device name as another device.
  const std::vector<FramePose>& cameraToCT = poses.cameraToCT;
  const std::vector<double>& timesS = poses.frameTimesS;
  try
  {
    checkFramePoses(cameraToCT);
    const auto& t = poses.ctFromSfm;
    if (t &&
      (!t->isValid() || t->translation.norm() > maxFramePoseDistanceMm ||
        !(t->scale < maxFramePoseDistanceMm)))
    {
      throw Error("CTFromSfM is not a finite similarity within 1 km of the CT origin");
    }
    if (!timesS.empty() &&
      (timesS.size() != cameraToCT.size() ||
        !std::all_of(timesS.begin(), timesS.end(), [](double v) { return std::isfinite(v); })))
    {
      throw Error(std::to_string(timesS.size()) + " frame times for " +
        std::to_string(cameraToCT.size()) + " poses: one finite time per pose, or none");
    }
    if (!poses.pictures.empty() && poses.pictures.size() != cameraToCT.size())
    {
      throw Error(std::to_string(poses.pictures.size()) + " pictures for " +
        std::to_string(cameraToCT.size()) + " poses: one per pose, or none");
    }
    for (const FramePicture& picture : poses.pictures)
    {
      if (picture.widthPx < 1 || picture.heightPx < 1 || picture.widthPx > 65535 ||
        picture.heightPx > 65535 ||
        picture.rgb.size() != static_cast<size_t>(picture.widthPx) * picture.heightPx * 3)
      {
        throw Error("a picture of " + std::to_string(picture.widthPx) + "x" +
          std::to_string(picture.heightPx) + " px holds " + std::to_string(picture.rgb.size()) +
          " bytes, not 3 per pixel");
      }
    }
    if (this->Options.imageName.empty() || this->Options.imageName.size() > maxDeviceNameLength)
    {
      throw Error("the image device name '" + this->Options.imageName + "' is not 1 to " +
        std::to_string(maxDeviceNameLength) + " characters");
    }
    for (const FrameWithoutPose& lost : poses.framesWithoutPose)
    {
      if (!timesS.empty() && !std::isfinite(lost.timeS))
      {
        throw Error("frame " + std::to_string(lost.frameId) +
          " without a pose has no finite time, and the poses have times");
      }
    }
    for (const DegradedPose& degraded : poses.degradedPoses)
    {
      if (std::none_of(cameraToCT.begin(), cameraToCT.end(),
            [&](const FramePose& p) { return p.frameId == degraded.frameId; }))
      {
        throw Error("frame " + std::to_string(degraded.frameId) +
          " is said to be degraded but has no pose among those published");
      }
    }
    for (const FramePose& pose : cameraToCT)
    {
      const std::string name = deviceNameOf(this->Options, pose.frameId);
      if (name.size() > maxDeviceNameLength)
      {
        throw Error("frame " + std::to_string(pose.frameId) + "'s device name " + name +
          " is longer than OpenIGTLink's " + std::to_string(maxDeviceNameLength) + " characters");
      }
    }
  }
  catch (const Error& e)
  {
    throw Error(std::string("pose server: refusing to publish: ") + e.what());
  }
  // The newest frame is now; the others as long before it as the video says.
  const double nowS =
    std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  double newestS = timesS.empty() ? 0.0 : *std::max_element(timesS.begin(), timesS.end());
  for (const FrameWithoutPose& lost : poses.framesWithoutPose)
  {
    newestS = timesS.empty() ? newestS : std::max(newestS, lost.timeS);
  }
  const auto stamp = [&](double frameTimeS)
  { return timesS.empty() ? nowS : nowS - (newestS - frameTimeS); };
  std::string messages = poses.ctFromSfm
    ? packTransform("CTFromSfM", intoRas(poses.ctFromSfm->matrix()), nowS)
    : std::string();
  // Poses and lost frames in the order of the video (by time; by frame id without times).
  std::vector<std::pair<double, std::string>> frames;
  for (size_t i = 0; i < cameraToCT.size(); ++i)
  {
    const double timeS = stamp(timesS.empty() ? 0.0 : timesS[i]);
    frames.emplace_back(timesS.empty() ? cameraToCT[i].frameId : timesS[i],
      (poses.pictures.empty() ? std::string()
                              : packImage(this->Options.imageName, poses.pictures[i], timeS)) +
        packTransform(deviceNameOf(this->Options, cameraToCT[i].frameId),
          intoRas(cameraToCT[i].cameraToWorld.matrix()), timeS));
    for (const DegradedPose& degraded : poses.degradedPoses)
    {
      if (degraded.frameId == cameraToCT[i].frameId)
      {
        frames.back().second += packTrackingDegraded(this->Options.cameraName, degraded, timeS);
      }
    }
  }
  for (const FrameWithoutPose& lost : poses.framesWithoutPose)
  {
    frames.emplace_back(timesS.empty() ? lost.frameId : lost.timeS,
      packTrackingLost(this->Options.cameraName, lost, stamp(lost.timeS)));
  }
  std::stable_sort(
    frames.begin(), frames.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& frame : frames)
  {
    messages += frame.second;
  }
  if (poses.verdict)
  {
    messages += packStatus(this->Options.cameraName, *poses.verdict, nowS);
  }
  this->Messages = messages;
  for (size_t i = this->Clients.size(); i-- > 0;)
  {
    this->Clients[i].pending += messages;
    if (!this->flush(this->Clients[i]))
    {
      this->dropSlowClient(i);
    }
  }
}

bool PoseStreamServer::allowed(std::uint32_t address) const
{
  if (this->Allowed.empty())
  {
    return true;
  }
  return std::any_of(this->Allowed.begin(), this->Allowed.end(),
    [&](const AddressBlock& block)
    {
      const std::uint32_t mask =
        block.prefixBits == 0 ? 0u : ~std::uint32_t(0) << (32 - block.prefixBits);
      return (ntohl(address) & mask) == (ntohl(block.address) & mask);
    });
}

void PoseStreamServer::countAndTell(int& counter, const std::string& what)
{
  ++counter;
  const std::string count = std::to_string(counter);
  if (count[0] == '1' && count.find_first_not_of('0', 1) == std::string::npos) // 1, 10, ...
  {
    const auto colon = what.find(": ");
    this->notice(what.substr(0, colon) + " (" + count + " so far)" + what.substr(colon));
  }
}

void PoseStreamServer::makeRoomFor(std::uint32_t address)
{
  // The connection of this address that has taken data least recently;
  // the vector holds clients in the order they came, so ties go to the oldest.
  size_t idlest = this->Clients.size();
  int fromAddress = 0;
  for (size_t i = 0; i < this->Clients.size(); ++i)
  {
    if (this->Clients[i].address != address)
    {
      continue;
    }
    ++fromAddress;
    if (idlest == this->Clients.size() ||
      this->Clients[i].lastRead < this->Clients[idlest].lastRead)
    {
      idlest = i;
    }
  }
  if (fromAddress >= this->Options.maxClientsPerAddress)
  {
    this->closeClient(idlest);
    this->countAndTell(this->Replaced,
      "closed a connection from " + addressText(address) + ": " +
        std::to_string(this->Options.maxClientsPerAddress) +
        " are kept per address (--max-clients-per-address); its most idle one made room for "
        "the new one");
  }
}

void PoseStreamServer::accept()
{
  for (;;)
  {
    sockaddr_in peer{};
    socklen_t length = sizeof(peer);
    const int fd = ::accept(this->Listener, reinterpret_cast<sockaddr*>(&peer), &length);
    if (fd < 0)
    {
      return; // no more pending connections (or a transient error)
    }
    const std::uint32_t address = peer.sin_addr.s_addr;
    if (!this->allowed(address))
    {
      close(fd);
      this->countAndTell(this->Refused,
        "refused a connection: " + addressText(address) +
          " is not an allowed client (--allow-client)");
      continue;
    }
    this->makeRoomFor(address);
    if (static_cast<int>(this->Clients.size()) >= this->Options.maxClients)
    {
      close(fd);
      this->countAndTell(this->Refused,
        "refused a connection: " + std::to_string(this->Options.maxClients) +
          " clients are served at once (--max-clients)");
      continue;
    }
    setNonBlocking(fd);
    Client client;
    client.fd = fd;
    client.address = address;
    client.pending = this->Messages;
    if (this->flush(client))
    {
      this->Clients.push_back(std::move(client));
    }
    else
    {
      close(fd);
    }
  }
}

bool PoseStreamServer::flush(Client& client)
{
  while (!client.pending.empty())
  {
    const ssize_t sent =
      send(client.fd, client.pending.data(), client.pending.size(), MSG_NOSIGNAL);
    if (sent < 0)
    {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
      {
        break;
      }
      return false;
    }
    client.pending.erase(0, static_cast<size_t>(sent));
    client.lastRead = std::chrono::steady_clock::now();
  }
  // One publication larger than the limit is still sent whole: a client
  // falls behind when it has more than that left.
  return client.pending.size() <=
    std::max(static_cast<size_t>(this->Options.maxPendingBytes), this->Messages.size());
}

void PoseStreamServer::drain(Client& client, bool& alive)
{
  char buffer[4096];
  for (;;)
  {
    const ssize_t got = recv(client.fd, buffer, sizeof(buffer), 0);
    if (got > 0)
    {
      continue; // requests and garbage alike are ignored
    }
    if (got == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR))
    {
      alive = false;
    }
    return;
  }
}

void PoseStreamServer::notice(const std::string& text) const
{
  if (this->Options.onNotice)
  {
    this->Options.onNotice(text);
  }
}

void PoseStreamServer::dropSlowClient(size_t index)
{
  // A failed flush: either the connection broke, or the client reads too slowly.
  const size_t unsent = this->Clients[index].pending.size();
  if (unsent > static_cast<size_t>(this->Options.maxPendingBytes))
  {
    ++this->Dropped;
    this->notice("dropped a client that does not keep up: " + std::to_string(unsent) +
      " bytes of poses unsent (above " + std::to_string(this->Options.maxPendingBytes) +
      "); it must reconnect for the poses");
  }
  this->closeClient(index);
}

void PoseStreamServer::dropStalledClients()
{
  const auto now = std::chrono::steady_clock::now();
  for (size_t i = this->Clients.size(); i-- > 0;)
  {
    const Client& client = this->Clients[i];
    const double stalledS = std::chrono::duration<double>(now - client.lastRead).count();
    if (!client.pending.empty() && stalledS > this->Options.stallTimeoutS)
    {
      ++this->Dropped;
      this->notice("dropped a client that stopped reading: " +
        std::to_string(client.pending.size()) + " bytes of poses untaken for " +
        std::to_string(static_cast<int>(stalledS)) + " s; it must reconnect for the poses");
      this->closeClient(i);
    }
  }
}

void PoseStreamServer::closeClient(size_t index)
{
  close(this->Clients[index].fd);
  this->Clients.erase(this->Clients.begin() + static_cast<std::ptrdiff_t>(index));
}

void PoseStreamServer::serve(const std::function<bool()>& keepRunning)
{
  while (keepRunning())
  {
    this->pump(100);
  }
}

bool PoseStreamServer::allSent() const
{
  return std::all_of(this->Clients.begin(), this->Clients.end(),
    [](const Client& client) { return client.pending.empty(); });
}

void PoseStreamServer::pump(int timeoutMs)
{
  std::vector<pollfd> fds;
  fds.push_back({ this->Listener, POLLIN, 0 });
  for (const Client& client : this->Clients)
  {
    fds.push_back(
      { client.fd, static_cast<short>(POLLIN | (client.pending.empty() ? 0 : POLLOUT)), 0 });
  }
  if (poll(fds.data(), fds.size(), std::max(timeoutMs, 0)) < 0 && errno != EINTR)
  {
    throw Error(std::string("the server's poll failed: ") + std::strerror(errno));
  }
  // Clients first (their indices match fds[1...]), newest last.
  for (size_t i = this->Clients.size(); i-- > 0;)
  {
    const short events = fds[i + 1].revents;
    bool alive = (events & (POLLERR | POLLNVAL)) == 0;
    if (alive && (events & (POLLIN | POLLHUP)))
    {
      this->drain(this->Clients[i], alive);
    }
    if (alive && (events & POLLOUT) && !this->flush(this->Clients[i]))
    {
      this->dropSlowClient(i);
      continue;
    }
    if (!alive)
    {
      this->closeClient(i);
    }
  }
  this->dropStalledClients();
  if (fds[0].revents & POLLIN)
  {
    this->accept();
  }
}

} // namespace vimlop
