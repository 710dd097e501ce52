#ifndef vimlop_CanonicalCommand_h
#define vimlop_CanonicalCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop canonical`: canonical camera poses along a (template) airway (V13 b).
void addCanonicalCommand(CLI::App& app);

} // namespace vimlop

#endif
