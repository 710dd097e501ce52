#ifndef vimlop_PoseServingFlags_h
#define vimlop_PoseServingFlags_h

#include <vimlop/Server/PoseServing.h>

namespace CLI
{
class App;
}

namespace vimlop
{

/**
 * @brief Adds --host, --port, --allow-remote, --max-clients and --duration-s
 * to `command`, stored into `options` (which must outlive the parse): the
 * flags of every subcommand that serves poses (VIMLOP::Server's servePoses).
 */
void addPoseServingOptions(CLI::App& command, PoseServingOptions& options);

} // namespace vimlop

#endif
