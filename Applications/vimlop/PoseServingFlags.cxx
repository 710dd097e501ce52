#include "PoseServingFlags.h"

#include <CLI/CLI.hpp>

namespace vimlop
{

void addPoseServingOptions(CLI::App& command, PoseServingOptions& options)
{
  command.add_option("--host", options.server.host, "address to listen on")->capture_default_str();
  command.add_option("--port", options.server.port, "TCP port (0: any free one)")
    ->capture_default_str();
  command.add_flag("--allow-remote", options.server.allowRemote, "allow a non-loopback address");
  command.add_option("--max-clients", options.server.maxClients, "clients served at once")
    ->capture_default_str();
  command
    .add_option("--duration-s", options.durationS, "stop after this many seconds (0: until Ctrl-C)")
    ->capture_default_str();
}

} // namespace vimlop
