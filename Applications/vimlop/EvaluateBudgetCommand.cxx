#include "Commands.h"

#include "CommandLine.h"
#include "TerminalEvaluationProgress.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/ErrorBudgetProtocol.h>
#include <vimlop/Imaging/CTVolumeIO.h>
#include <vimlop/Rendering/OffscreenRendering.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>

namespace vimlop
{

namespace
{

struct BudgetCommand
{
  std::string ct, out;
  ErrorBudgetOptions protocol;
  std::string sources;
  std::string levels = joinNumbers(protocol.levels);
  std::string methods = "vimlop,imlp,trimmed-icp";
  bool json = false;
  std::string starts = "canonical,perturbed";
  std::string perturbMm = joinNumbers({ protocol.perturbMinMm, protocol.perturbMaxMm });
  std::string perturbDeg = joinNumbers({ protocol.perturbMinDeg, protocol.perturbMaxDeg });
  bool noReport = false;
};

void runBudget(BudgetCommand c)
{
  namespace fs = std::filesystem;
  ErrorBudgetOptions& o = c.protocol;
  if (!c.sources.empty())
  {
    o.sources = parseList(c.sources, "--sources");
  }
  o.levels = parseNumbers(c.levels, "--levels");
  o.methods.clear();
  for (const std::string& m : parseList(c.methods, "--methods"))
  {
    o.methods.push_back(registrationMethodFromString(m));
  }
  const std::vector<std::string> starts = parseList(c.starts, "--starts");
  o.canonicalStarts = o.perturbedStarts = false;
  for (const std::string& s : starts)
  {
    if (s != "canonical" && s != "perturbed")
    {
      throw Error("--starts: expected canonical and/or perturbed, got '" + s + "'");
    }
    (s == "canonical" ? o.canonicalStarts : o.perturbedStarts) = true;
  }
  std::tie(o.perturbMinMm, o.perturbMaxMm) = parseRange(c.perturbMm, "--perturb-mm");
  std::tie(o.perturbMinDeg, o.perturbMaxDeg) = parseRange(c.perturbDeg, "--perturb-deg");
  o.workFolder = (fs::path(c.out) / "work").string();
  o.validate();
  requireOffscreenRendering("vimlop evaluate budget");
  fs::create_directories(c.out);
  const ErrorBudgetReport report =
    runErrorBudgetProtocol(readCTVolume(c.ct), o, terminalEvaluationProgress());
  writeJsonFile(report.toJson(), (fs::path(c.out) / "p5.json").string());
  if (!c.noReport)
  {
    writeErrorBudgetPage(report, (fs::path(c.out) / "report").string());
  }
  std::error_code ec;
  fs::remove_all(o.workFolder, ec);
  printSummary({ report.summaryLines(), report.toJson() }, c.json);
}

} // namespace

void addEvaluateBudgetCommand(CLI::App& evaluate)
{
  auto c = std::make_shared<BudgetCommand>();
  ErrorBudgetOptions& o = c->protocol;
  CLI::App* p5 = evaluate.add_subcommand("budget",
    "P5, the error budget: each error source of the simulated world alone and all together "
    "(the clinical world), over many sequences; camera errors, TRE, success and the failure "
    "flag's AUC of V-IMLOP, IMLP and trimmed ICP from canonical and perturbed starts; "
    "OUT/p5.json and OUT/report");
  p5->add_option("--ct", c->ct, "the CT: the template, and the patient before deformation")
    ->required();
  p5->add_option("--out", c->out, "output folder")->required();
  p5->add_option("--seeds", o.seeds, "sequences per condition")
    ->capture_default_str()
    ->check(CLI::Range(1, 10000));
  p5->add_option("--first-seed", o.firstSeed, "seed of the first sequence")->capture_default_str();
  p5->add_option("--frames", o.frames, "frames per sequence")
    ->capture_default_str()
    ->check(CLI::Range(3, 1000));
  p5->add_option("--sources", c->sources,
    "the sources varied alone (default: all; see Documentation/Simulation.md)");
  p5->add_option("--levels", c->levels,
      "each source's values as fractions of its clinical value, e.g. 0.5,1,2")
    ->capture_default_str();
  p5->add_flag("!--no-ideal", o.ideal, "skip the ideal world");
  p5->add_flag("!--no-clinical", o.clinical, "skip the clinical world (every source together)");
  p5->add_option("--methods", c->methods, "methods compared")->capture_default_str();
  p5->add_option("--starts", c->starts, "kinds of start: canonical, perturbed")
    ->capture_default_str();
  p5->add_option("--perturb-mm", c->perturbMm, "range of the perturbed start's translation, mm")
    ->capture_default_str();
  p5->add_option("--perturb-deg", c->perturbDeg, "range of the perturbed start's rotation, deg")
    ->capture_default_str();
  p5->add_option("--success-mm", o.successMm,
      "a registration succeeds when its mean camera position error is at most this, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p5->add_option("--good-mm", o.goodMm,
      "a registration is good when its mean camera position error is below this, mm; the "
      "failure flag's false flags are flagged good ones")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  p5->add_flag("--no-report", c->noReport, "skip the report page");
  addPipelineOptions(*p5, o.pipeline);
  addJsonFlag(*p5, c->json);
  p5->callback([c] { runBudget(*c); });
}

} // namespace vimlop
