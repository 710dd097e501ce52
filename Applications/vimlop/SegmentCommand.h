#ifndef vimlop_SegmentCommand_h
#define vimlop_SegmentCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop segment`: the nasal airway surface of a head CT.
void addSegmentCommand(CLI::App& app);

} // namespace vimlop

#endif
