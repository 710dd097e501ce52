#ifndef vimlop_EvaluateWarpCommand_h
#define vimlop_EvaluateWarpCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `warp` (protocol P4, template warp) to the `vimlop evaluate` group.
void addEvaluateWarpCommand(CLI::App& evaluate);

} // namespace vimlop

#endif
