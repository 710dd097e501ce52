#ifndef vimlop_EvaluateCommand_h
#define vimlop_EvaluateCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/**
 * @brief Adds `vimlop evaluate <protocol>` with the synthetic experiment (P1);
 * returns it so that other protocols can add themselves.
 */
CLI::App* addEvaluateCommand(CLI::App& app);

} // namespace vimlop

#endif
