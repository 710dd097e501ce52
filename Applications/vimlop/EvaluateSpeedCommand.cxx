#include "Commands.h"

#include "CommandLine.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Evaluation/SpeedBenchmark.h>
#include <vimlop/Rendering/OffscreenRendering.h>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <memory>

#include <unistd.h>

namespace vimlop
{

namespace
{

struct SpeedCommand
{
  SpeedBenchmarkOptions benchmark;
  std::string frames = "6,30,60,100";
  std::string threads = "1,2";
  std::string out, keep;
  bool json = false;
};

/// Removes the temporary work folder (not a --keep folder) unless a child failed.
struct TemporaryFolder
{
  std::filesystem::path path;
  ~TemporaryFolder()
  {
    std::error_code ec;
    if (!this->path.empty())
    {
      std::filesystem::remove_all(this->path, ec);
    }
  }
};

void runSpeed(SpeedCommand c)
{
  namespace fs = std::filesystem;
  SpeedBenchmarkOptions& o = c.benchmark;
  o.frameCounts = SpeedBenchmarkOptions::parseCounts(c.frames, "--frames");
  o.threadCounts = SpeedBenchmarkOptions::parseCounts(c.threads, "--threads");
  o.workFolder = c.keep.empty() ? "(temporary)" : c.keep;
  o.validate();
  if (fs::path(c.out).extension() != ".json")
  {
    throwFileError(c.out, "the output is JSON: name it *.json");
  }
  if (!fs::exists(o.ctPath))
  {
    throwFileError(o.ctPath, "no such file or folder");
  }
  // simulate and register render (the frames, the registered video, the
  // report): without a display every child would fail, so say it once here.
  requireOffscreenRendering("vimlop evaluate speed");
  TemporaryFolder temporary;
  if (c.keep.empty())
  {
    temporary.path = fs::temp_directory_path() / ("vimlop-speed-" + std::to_string(::getpid()));
    o.workFolder = temporary.path.string();
  }
  // The commit before the runs: the tree may change while they go on.
  const std::string commit = sourceCommit(VIMLOP_SOURCE_DIR);
  SpeedBenchmarkReport report;
  try
  {
    report = runSpeedBenchmark(o, &std::cerr);
  }
  catch (const Error&)
  {
    // The message points at a child's log in the work folder: keep it.
    temporary.path.clear();
    throw;
  }
  report.version = VIMLOP_VERSION;
  report.commit = commit;
  writeJsonFile(report.toJson(), c.out);
  for (const std::string& w : report.warnings())
  {
    std::cerr << "vimlop: warning: " << w << "\n";
  }
  CommandSummary summary{ report.tableLines(), report.toJson() };
  const std::vector<std::string> scaling = report.scalingLines();
  summary.lines.insert(summary.lines.end(), scaling.begin(), scaling.end());
  summary.lines.push_back("wrote '" + c.out + "'");
  printSummary(summary, c.json);
}

} // namespace

void addEvaluateSpeedCommand(CLI::App& evaluate)
{
  auto c = std::make_shared<SpeedCommand>();
  CLI::App* speed = evaluate.add_subcommand("speed",
    "The main job's speed: simulated sequences of several lengths, each registered by "
    "`vimlop register` as a child process on each thread count; wall time per stage, peak "
    "memory and thread scaling as a table and JSON. Needs a display (xvfb-run -a).");
  speed->add_option("--ct", c->benchmark.ctPath, "the CT (simulated world and register's input)")
    ->required();
  speed->add_option("--out", c->out, "output JSON")->required();
  speed->add_option("--frames", c->frames, "sequence lengths, frames")->capture_default_str();
  speed->add_option("--threads", c->threads, "thread counts of each registration")
    ->capture_default_str();
  speed->add_option("--seed", c->benchmark.seed, "the simulation's seed")->capture_default_str();
  speed->add_option("--step-mm", c->benchmark.stepMm,
    "the simulated endoscope's advance per frame, mm (default: simulate's, 0.5; long sequences "
    "need less to fit in the airway, e.g. 0.2 for 100 frames)");
  speed
    ->add_option("--upright-deg", c->benchmark.uprightRollDeg,
      "the scope held upright within this many degrees, as in the demo (negative: any roll, "
      "which fails from canonical poses)")
    ->capture_default_str();
  speed->add_option("--keep", c->keep,
    "keep the sequences, results and the children's logs in this folder (default: a "
    "temporary folder, removed)");
  addJsonFlag(*speed, c->json);
  speed->callback([c] { runSpeed(*c); });
}

} // namespace vimlop
