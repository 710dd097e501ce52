#ifndef vimlop_ServeCommand_h
#define vimlop_ServeCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop serve`: camera poses to navigation software over OpenIGTLink.
void addServeCommand(CLI::App& app);

} // namespace vimlop

#endif
