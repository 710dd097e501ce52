#ifndef vimlop_SfmCommand_h
#define vimlop_SfmCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop sfm`: structure from motion of a sequence (built in, or a COLMAP import).
void addSfmCommand(CLI::App& app);

} // namespace vimlop

#endif
