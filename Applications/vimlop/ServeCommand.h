#ifndef vimlop_ServeCommand_h
#define vimlop_ServeCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop serve`: the camera poses of a pose file or a result folder to
/// navigation software over OpenIGTLink (serving itself is in PoseServing.h).
void addServeCommand(CLI::App& app);

} // namespace vimlop

#endif
