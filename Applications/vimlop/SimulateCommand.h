#ifndef vimlop_SimulateCommand_h
#define vimlop_SimulateCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop simulate`: a virtual endoscope sequence in the airway of a CT.
void addSimulateCommand(CLI::App& app);

} // namespace vimlop

#endif
