#ifndef vimlop_WarpCommand_h
#define vimlop_WarpCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop warp`: template CT to patient CT, with meshes and poses carried over.
void addWarpCommand(CLI::App& app);

} // namespace vimlop

#endif
