#ifndef vimlop_InfoCommand_h
#define vimlop_InfoCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop info <file>`: what a CT, mesh or intrinsics file holds.
void addInfoCommand(CLI::App& app);

} // namespace vimlop

#endif
