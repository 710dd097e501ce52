#include <vimlop/Cohort/CohortRowCommand.h>

namespace vimlop
{

const std::vector<CohortRowCommand>& cohortRowCommands()
{
  using Output = CohortRowCommand::Output;
  using Figures = CohortRowCommand::Figures;
  // Rough wall times at default settings on 2 cores, from the README's
  // figures: the demo's 30 frames from canonical poses for register.
  static const std::vector<CohortRowCommand> commands = {
    { { "register" }, Output::Folder, "result.json", 3, Figures::Registration, true, true, 30.0 },
    { { "evaluate", "synthetic" }, Output::FileInFolder, "p1.json", -1, Figures::ProtocolReport,
      true, false, 20.0 },
    { { "evaluate", "video" }, Output::FileInFolder, "p2.json", -1, Figures::ProtocolReport, true,
      false, 40.0 },
    { { "evaluate", "perturbation" }, Output::Folder, "p3.json", -1, Figures::ProtocolReport, true,
      false, 300.0 },
    { { "evaluate", "warp" }, Output::FileInFolder, "p4.json", -1, Figures::ProtocolReport, false,
      false, 120.0 },
    { { "evaluate", "budget" }, Output::Folder, "p5.json", -1, Figures::ProtocolReport, true, false,
      1800.0 },
  };
  return commands;
}

const CohortRowCommand* findCohortRowCommand(const std::vector<std::string>& words)
{
  for (const CohortRowCommand& command : cohortRowCommands())
  {
    if (command.words == words)
    {
      return &command;
    }
  }
  return nullptr;
}

} // namespace vimlop
