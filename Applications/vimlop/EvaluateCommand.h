#ifndef vimlop_EvaluateCommand_h
#define vimlop_EvaluateCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop evaluate <protocol>`: the evaluation protocols (P1, ...).
void addEvaluateCommand(CLI::App& app);

} // namespace vimlop

#endif
