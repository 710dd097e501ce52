#ifndef vimlop_ContoursCommand_h
#define vimlop_ContoursCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop contours`: occluding contours with normals in every frame of a sequence.
void addContoursCommand(CLI::App& app);

} // namespace vimlop

#endif
