#ifndef vimlop_ReportCommand_h
#define vimlop_ReportCommand_h

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop report`: the rendered report of a result folder and/or a perturbation study.
void addReportCommand(CLI::App& app);

} // namespace vimlop

#endif
