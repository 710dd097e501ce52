// vimlop: the command-line program. Each subcommand lives in its own file and
// registers itself here; errors the user can act on (vimlop::Error, and a
// command line CLI11 cannot parse) end the program with one `vimlop: error:`
// line on stderr and exit code 1.

#include "CommandLine.h"
#include "Commands.h"
#include <vimlop/Core/Error.h>

#include <CLI/CLI.hpp>

#include <vtkObject.h>

#include <exception>
#include <iostream>

int main(int argc, char** argv)
{
  // VTK's and ITK's own diagnostics would add lines of their own to ours:
  // every problem reaches the user as one vimlop::Error line instead.
  vtkObject::GlobalWarningDisplayOff();
  vimlop::commandWords().assign(argv, argv + argc);
  CLI::App app{ "vimlop: video-CT registration for endoscopic sinus surgery (V-IMLOP)" };
  app.set_version_flag("--version", std::string("vimlop ") + VIMLOP_VERSION);
  app.require_subcommand(1);
  // One config file for every command: a TOML file whose [register],
  // [simulate], ... sections hold the options of that command ("name =
  // value", the long name without "--"); the command line wins. Given after
  // the command's name too (it falls through to here).
  app.set_config("--config", "",
    "read options from a TOML file: a section per command ([register], ...) of 'name = value' "
    "lines, the long option names without '--' (e.g. fps = 25, no-video = true); the command "
    "line wins. vimlop register writes its options back as config.toml in the result folder");
  app.fallthrough();
  app.allow_config_extras(CLI::config_extras_mode::error);
  vimlop::addInfoCommand(app);
  vimlop::addSegmentCommand(app);
  vimlop::addServeCommand(app);
  vimlop::addExportCommand(app);
  vimlop::addWarpCommand(app);
  CLI::App* evaluate = vimlop::addEvaluateCommand(app);
  vimlop::addEvaluateWarpCommand(*evaluate);
  vimlop::addEvaluateBudgetCommand(*evaluate);
  vimlop::addEvaluateSpeedCommand(*evaluate);
  vimlop::addSimulateCommand(app);
  vimlop::addContoursCommand(app);
  vimlop::addSfmCommand(app);
  vimlop::addReportCommand(app);
  vimlop::addRegisterCommand(app);
  vimlop::addTrackCommand(app);
  vimlop::addCanonicalCommand(app);
  vimlop::addCalibrateCommand(app);
  vimlop::addCohortCommand(app);
  if (const std::string unknown = vimlop::unknownSubcommandMessage(app, argc, argv);
      !unknown.empty())
  {
    std::cerr << "vimlop: error: " << unknown << "\n";
    return 1;
  }
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    if (e.get_exit_code() == 0)
    {
      return app.exit(e); // --help, --version
    }
    const CLI::Option* config = app.get_config_ptr();
    std::cerr << "vimlop: error: "
              << vimlop::parseErrorMessage(
                   e, config && config->count() > 0 ? config->as<std::string>() : std::string())
              << "\n";
    return 1;
  }
  catch (const vimlop::Error& e)
  {
    std::cerr << "vimlop: error: " << e.what() << "\n";
    return 1;
  }
  catch (const vimlop::ExitRequest& e)
  {
    return e.code;
  }
  catch (const std::exception& e)
  {
    std::cerr << "vimlop: internal error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
