#ifndef vimlop_PoseStreamServer_h
#define vimlop_PoseStreamServer_h

#include <vimlop/Server/ServedPoses.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief How the camera poses are named on the wire.
enum class CameraDeviceNames
{
  /// One device (`PoseStreamServerOptions::cameraName`) updated frame after
  /// frame, each message stamped with its frame's time: one moving camera,
  /// as 3D Slicer and PLUS show a tracked tool.
  OneMovingCamera,
  /// One device per frame, `VideoCamera_<frame id>`: every pose stays
  /// available as its own transform.
  OnePerFrame
};

/// @brief Where and how PoseStreamServer listens.
struct PoseStreamServerOptions
{
  /// Address to listen on (default 127.0.0.1, loopback only): an IPv4
  /// address or a host name that resolves to one (e.g. localhost).
  std::string host = "127.0.0.1";
  /// TCP port (default 18944, OpenIGTLink's); 0 picks a free one.
  int port = 18944;
  /// Listen on a non-loopback address (default off: refused).
  bool allowRemote = false;
  /// Clients served at once (default 512, so that hundreds of idle
  /// connections still leave room for the navigation system's); further
  /// connections are closed. Each takes a file descriptor: the server raises
  /// its own limit to fit, or refuses to start.
  int maxClients = 512;
  /// Connections kept from one address (default 64): a new one beyond it
  /// replaces that address's most idle connection (the one that has taken
  /// data least recently; the oldest among equals), so one host, or a client
  /// that reconnects and leaves dead connections behind, cannot fill the
  /// server, while the next connection from it is still served. Local
  /// programs share 127.0.0.1.
  int maxClientsPerAddress = 64;
  /**
   * The only addresses allowed to connect, as IPv4 addresses or CIDR blocks
   * ("10.1.2.3", "10.1.0.0/16"; add "127.0.0.1" to keep local programs);
   * empty (the default): every address that can reach the socket. Other
   * connections are closed at once and told about. OpenIGTLink has no
   * authentication: this narrows who receives poses on a navigation
   * network, it does not prove who they are.
   */
  std::vector<std::string> allowedClients;
  /// A client whose unsent data exceeds this is dropped (default 1 MiB); one
  /// publication larger than this is still sent whole (the limit is then its size).
  int maxPendingBytes = 1 << 20;
  /// A client that has taken none of the data pending for it for this long
  /// is dropped (default 10 s): the read timeout of a client that stopped reading.
  double stallTimeoutS = 10.0;
  /**
   * Told, in one line, whenever the server refuses a connection (at the 1st,
   * 10th, 100th ... refusal, with the count) or drops a client that does not
   * keep up: no pose is lost without a word. Empty: nobody is told.
   */
  std::function<void(const std::string&)> onNotice;
  /// How camera poses are named (default one moving camera).
  CameraDeviceNames cameraNames = CameraDeviceNames::OneMovingCamera;
  /// The moving camera's device name (default CameraToCT; 1 to 20
  /// characters, OpenIGTLink's limit), also the STATUS messages' device.
  std::string cameraName = "CameraToCT";
  /// The device name of the frames' IMAGE messages (default CameraImage; 1
  /// to 20 characters), when the poses come with pictures.
  std::string imageName = "CameraImage";
};

/// @brief `options` whose notices go to stderr as one line, "<label>: warning:
/// <notice>": how the commands that serve poses tell them.
PoseStreamServerOptions withNoticesOnStderr(
  PoseStreamServerOptions options, const std::string& label);

/**
 * @brief Streams registration results to navigation software over OpenIGTLink.
 *
 * Every client that connects receives the last publication, then every
 * new one: `CTFromSfM` (the similarity T, mapping the SfM frame into the
 * CT), one TRANSFORM per frame (each frame's camera-to-CT pose; camera axes
 * x right, y down, z forward), in the order of the video, named by
 * `cameraNames`, each preceded, when the poses come with pictures, by its
 * frame's picture as an IMAGE message (`imageName`, 8-bit RGB, the same
 * time; rows top first, the image's j axis pointing down, so that 3D Slicer
 * shows it upright), a STATUS message (code NOT_PRESENT, error name
 * `TrackingLost`, sub-code the frame id) in the place of each frame without
 * a pose, a STATUS message (code UNKNOWN_ERROR, error name
 * `TrackingDegraded`, sub-code the frame id) right after each pose its
 * tracker does not vouch for, and, for a registration's poses, a STATUS message with its
 * verdict (code OK, or error name `RegistrationFlagged` for a result flagged
 * as a failure). Each message carries a wall-clock timestamp: the newest
 * frame is stamped with the moment of publication, the others earlier by
 * their frame times' difference (all with that moment when the times are
 * unknown), so that times increase along the video and none lies in the
 * future. By the
 * OpenIGTLink protocol the matrices are in RAS (mm): VIMLOP's LPS CT frame is
 * converted (see CoordinateFrames.h), as 3D Slicer's OpenIGTLinkIF expects.
 *
 * `CTFromSfM` is a similarity, and its matrix carries the scale as it is:
 * [s R_ras  t_ras; 0 0 0 1], whose upper-left 3 x 3 block is s times a
 * rotation (each column has length s, its determinant is s³) and whose
 * translation is in mm. SfM-frame data (points, a mesh) multiplied by it
 * lands in the CT in mm, e.g. under a linear transform node in 3D Slicer;
 * a receiver that needs a rigid transform divides the block by s. Camera
 * poses are rigid (s = 1).
 *
 * One thread, non-blocking sockets and poll(): a client that sends garbage,
 * disconnects early, never reads, or comes with many others cannot crash or
 * stall the server. What clients send is read and discarded.
 */
class PoseStreamServer
{
public:
  /**
   * @brief Binds and listens.
   * @throws vimlop::Error for a non-loopback host without allowRemote, an
   * invalid address, or a port that cannot be bound.
   */
  explicit PoseStreamServer(const PoseStreamServerOptions& options);
  ~PoseStreamServer();
  PoseStreamServer(const PoseStreamServer&) = delete;
  PoseStreamServer& operator=(const PoseStreamServer&) = delete;

  /// @brief The port listened on (the chosen one when the options said 0).
  int port() const { return this->Port; }

  /**
   * @brief Sets the poses sent to new clients and sends them to connected ones.
   * @throws vimlop::Error, publishing nothing, for poses checkFramePoses()
   * refuses, a CTFromSfM that is not a finite similarity within 1 km of
   * the CT origin, frame times that are not one finite number per pose, or
   * a frame id whose device name would be longer than OpenIGTLink's 20
   * characters.
   */
  void publish(const ServedPoses& poses);

  /// @brief Serves until `keepRunning()` returns false (checked about every 100 ms).
  void serve(const std::function<bool()>& keepRunning);

  /**
   * @brief Serves once: accepts new clients, sends what is pending, reads
   * and discards what clients sent, drops the dead and the stalled. Waits
   * at most `timeoutMs` (0: not at all) for something to happen, so that a
   * loop that computes poses (a tracker) can serve between frames.
   */
  void pump(int timeoutMs);

  /// @brief True when every connected client has taken all that was sent to it.
  bool allSent() const;

  /// @brief Clients connected now.
  int clientCount() const { return static_cast<int>(this->Clients.size()); }
  /// @brief Connections refused because maxClients were served, or from
  /// an address not in allowedClients, so far.
  int refusedCount() const { return this->Refused; }
  /// @brief Connections closed to make room for a newer one from the same
  /// address (maxClientsPerAddress), so far.
  int replacedCount() const { return this->Replaced; }
  /// @brief Clients dropped because they did not read what was sent (more
  /// than maxPendingBytes unsent, or nothing taken for stallTimeoutS), so far.
  int droppedCount() const { return this->Dropped; }

private:
  struct Client
  {
    int fd = -1;
    /// The peer's IPv4 address, in network byte order.
    std::uint32_t address = 0;
    std::string pending;
    /// When the client last took bytes (or connected).
    std::chrono::steady_clock::time_point lastRead = std::chrono::steady_clock::now();
  };

  /// An address and the number of leading bits that must match.
  struct AddressBlock
  {
    std::uint32_t address = 0;
    int prefixBits = 32;
  };

  static AddressBlock parseAddressBlock(const std::string& text);
  void accept();
  bool allowed(std::uint32_t address) const;
  void makeRoomFor(std::uint32_t address);
  void countAndTell(int& counter, const std::string& what);
  bool flush(Client& client);
  void drain(Client& client, bool& alive);
  void closeClient(size_t index);
  void dropSlowClient(size_t index);
  void dropStalledClients();
  void notice(const std::string& text) const;

  PoseStreamServerOptions Options;
  int Listener = -1;
  int Port = 0;
  std::string Messages; ///< the packed messages of the last publish()
  std::vector<Client> Clients;
  std::vector<AddressBlock> Allowed;
  int Refused = 0;
  int Replaced = 0;
  int Dropped = 0;
};

} // namespace vimlop

#endif
