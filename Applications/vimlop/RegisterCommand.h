#ifndef vimlop_RegisterCommand_h
#define vimlop_RegisterCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/**
 * @brief Adds `vimlop register`: CT (or airway mesh) and video in; result
 * folder, registered video and report out (exit code 0, or 3 when the result
 * is flagged as a failure, 130 when interrupted, 1 for an error).
 */
void addRegisterCommand(CLI::App& app);

} // namespace vimlop

#endif
