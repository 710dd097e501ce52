#include "ServeCommand.h"

#include "Error.h"
#include "FramePoseIO.h"
#include "PoseStreamServer.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>

namespace vimlop
{

namespace
{

volatile std::sig_atomic_t stopRequested = 0;

void requestStop(int)
{
  stopRequested = 1;
}

struct ServeOptions
{
  std::string poses;
  PoseStreamServerOptions server;
  double durationS = 0.0;
};

void runServe(const ServeOptions& options)
{
  const std::vector<FramePose> poses = readFramePoses(options.poses);
  PoseStreamServer server(options.server);
  server.publish(nullptr, poses);
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  std::printf("vimlop serve: %zu camera poses on %s:%d (OpenIGTLink TRANSFORM, RAS mm); Ctrl-C stops\n",
    poses.size(), options.server.host.c_str(), server.port());
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  server.serve([&] {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return !stopRequested && (options.durationS <= 0.0 || elapsed < options.durationS);
  });
  std::printf("vimlop serve: stopped\n");
}

} // namespace

void addServeCommand(CLI::App& app)
{
  auto options = std::make_shared<ServeOptions>();
  CLI::App* serve = app.add_subcommand("serve",
    "Send camera poses to navigation software (3D Slicer OpenIGTLinkIF, PLUS, ...) over OpenIGTLink");
  serve->add_option("--poses", options->poses,
      "camera poses in CT (JSON, as written by vimlop warp); each becomes VideoCamera_<frame_id>")
    ->required();
  serve->add_option("--host", options->server.host, "address to listen on")->capture_default_str();
  serve->add_option("--port", options->server.port, "TCP port (0: any free one)")->capture_default_str();
  serve->add_flag("--allow-remote", options->server.allowRemote, "allow a non-loopback address");
  serve->add_option("--max-clients", options->server.maxClients, "clients served at once")->capture_default_str();
  serve->add_option("--duration-s", options->durationS, "stop after this many seconds (0: until Ctrl-C)")
    ->capture_default_str();
  serve->callback([options] { runServe(*options); });
}

} // namespace vimlop
