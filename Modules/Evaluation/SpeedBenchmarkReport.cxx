#include <vimlop/Evaluation/SpeedBenchmarkReport.h>

#include <vimlop/Core/TextFormat.h>

#include <algorithm>

namespace vimlop
{

namespace
{

/// A stage's wall time, or the total's or the result's.
double wallOf(const SpeedBenchmarkRun& run, const std::string& stage)
{
  if (stage == "total")
  {
    return run.wallS;
  }
  if (stage == "result")
  {
    return run.resultS();
  }
  const StageTimings::Stage* s = run.stages.find(stage);
  return s ? s->wallS : 0.0;
}

std::string ratioText(const std::optional<double>& ratio)
{
  return ratio ? formatText("%.2f", *ratio) : std::string("-");
}

nlohmann::json ratioJson(const std::optional<double>& ratio)
{
  return ratio ? nlohmann::json(*ratio) : nlohmann::json(nullptr);
}

nlohmann::json loadJson(const std::array<double, 3>& load)
{
  return load[0] >= 0.0 ? nlohmann::json(load) : nlohmann::json(nullptr);
}

} // namespace

bool SpeedBenchmarkRun::isOutputStage(const std::string& name)
{
  for (const char* output :
    { "record", "poses", "pictures", "video", "camera_path", "result_json", "report" })
  {
    if (name == output)
    {
      return true;
    }
  }
  return false;
}

double SpeedBenchmarkRun::resultS() const
{
  if (const StageTimings::Mark* usable = this->stages.findMark("result_usable"))
  {
    return usable->atWallS;
  }
  double sum = 0.0;
  for (const StageTimings::Stage& s : this->stages.stages())
  {
    sum += isOutputStage(s.name) ? 0.0 : s.wallS;
  }
  return sum;
}

double SpeedBenchmarkRun::outputsS() const
{
  double sum = 0.0;
  for (const StageTimings::Stage& s : this->stages.stages())
  {
    sum += isOutputStage(s.name) ? s.wallS : 0.0;
  }
  return sum;
}

double SpeedBenchmarkRun::cpuPerWall() const
{
  return this->wallS > 0.0 ? (this->userCpuS + this->systemCpuS) / this->wallS : 0.0;
}

double SpeedBenchmarkRun::unaccountedS() const
{
  return this->wallS - this->stages.totalWallS();
}

SpeedBenchmarkReport::Scaling SpeedBenchmarkReport::scaling(
  const SpeedBenchmarkRun& base, const SpeedBenchmarkRun& run, const std::string& stage)
{
  // Below a millisecond the ratio says more about the clock than the code.
  constexpr double leastS = 1e-3;
  const double baseS = wallOf(base, stage);
  const double runS = wallOf(run, stage);
  Scaling s;
  if (baseS >= leastS && runS >= leastS && run.threads > 0)
  {
    s.speedup = baseS / runS;
    s.efficiency = *s.speedup * base.threads / run.threads;
  }
  return s;
}

std::vector<std::string> SpeedBenchmarkReport::stageNames() const
{
  std::vector<std::string> names;
  for (const SpeedBenchmarkRun& run : this->runs)
  {
    for (const StageTimings::Stage& s : run.stages.stages())
    {
      if (std::find(names.begin(), names.end(), s.name) == names.end())
      {
        names.push_back(s.name);
      }
    }
  }
  return names;
}

const SpeedBenchmarkRun* SpeedBenchmarkReport::baseOf(const SpeedBenchmarkRun& run) const
{
  const SpeedBenchmarkRun* base = nullptr;
  for (const SpeedBenchmarkRun& r : this->runs)
  {
    if (r.frames == run.frames && (!base || r.threads < base->threads))
    {
      base = &r;
    }
  }
  return base;
}

std::vector<std::string> SpeedBenchmarkReport::tableLines() const
{
  const std::vector<std::string> names = this->stageNames();
  std::vector<int> widths;
  std::string header = "frames threads   wall s result s";
  for (const std::string& n : names)
  {
    widths.push_back(std::max(8, static_cast<int>(n.size()) + 1));
    header += formatText("%*s", widths.back(), n.c_str());
  }
  header += " CPU/wall  peak MiB";
  std::vector<std::string> lines = { header };
  for (const SpeedBenchmarkRun& run : this->runs)
  {
    std::string line =
      formatText("%6d %7d %8.2f %8.2f", run.frames, run.threads, run.wallS, run.resultS());
    for (size_t i = 0; i < names.size(); ++i)
    {
      const StageTimings::Stage* s = run.stages.find(names[i]);
      line += s ? formatText("%*.2f", widths[i], s->wallS) : formatText("%*s", widths[i], "-");
    }
    line += formatText(" %8.2f %9.0f%s", run.cpuPerWall(), run.peakResidentMiB,
      run.flaggedAsFailure ? "  (flagged)" : "");
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> SpeedBenchmarkReport::warnings() const
{
  std::vector<std::string> lines;
  const int cpus = this->machine.logicalCpus;
  const double busiest = std::max(this->machine.loadAverage[0], this->loadAverageEnd[0]);
  if (cpus > 0 && busiest >= cpus)
  {
    lines.push_back(formatText("the machine was busy: a load average of %.2f on %d logical "
                               "processors; the times include waiting for them, and the thread "
                               "scaling says little",
      busiest, cpus));
  }
  for (const SpeedBenchmarkRun& run : this->runs)
  {
    // One thread alone keeps one processor busy, unless others take it.
    if (run.threads == 1 && run.wallS > 0.0 && run.cpuPerWall() < 0.8)
    {
      lines.push_back(formatText("%d frames, 1 thread: the run had the processor %.0f %% of its "
                                 "wall time (other processes took the rest)",
        run.frames, 100.0 * run.cpuPerWall()));
    }
  }
  return lines;
}

std::vector<std::string> SpeedBenchmarkReport::scalingLines() const
{
  std::vector<std::string> lines;
  for (const SpeedBenchmarkRun& run : this->runs)
  {
    const SpeedBenchmarkRun* base = this->baseOf(run);
    if (!base || base == &run || base->threads == run.threads)
    {
      continue;
    }
    std::string line = formatText("%d frames, %d -> %d threads: speed-up (efficiency) total %s "
                                  "(%s), result %s (%s);",
      run.frames, base->threads, run.threads,
      ratioText(scaling(*base, run, "total").speedup).c_str(),
      ratioText(scaling(*base, run, "total").efficiency).c_str(),
      ratioText(scaling(*base, run, "result").speedup).c_str(),
      ratioText(scaling(*base, run, "result").efficiency).c_str());
    for (const StageTimings::Stage& s : run.stages.stages())
    {
      const Scaling k = scaling(*base, run, s.name);
      line += formatText(" %s %s (%s)", s.name.c_str(), ratioText(k.speedup).c_str(),
        ratioText(k.efficiency).c_str());
    }
    lines.push_back(line);
  }
  return lines;
}

nlohmann::json SpeedBenchmarkReport::toJson() const
{
  nlohmann::json machineJson = this->machine.toJson();
  machineJson.erase("load_average");
  machineJson["load_average_start"] = loadJson(this->machine.loadAverage);
  machineJson["load_average_end"] = loadJson(this->loadAverageEnd);
  nlohmann::json sequences = nlohmann::json::array();
  for (const auto& [frames, seconds] : this->simulateWallS)
  {
    sequences.push_back({ { "frames", frames }, { "simulate_wall_s", seconds } });
  }
  nlohmann::json runsJson = nlohmann::json::array();
  nlohmann::json scalingJson = nlohmann::json::array();
  for (const SpeedBenchmarkRun& run : this->runs)
  {
    runsJson.push_back({ { "frames", run.frames }, { "threads", run.threads },
      { "wall_s", run.wallS }, { "result_s", run.resultS() }, { "outputs_s", run.outputsS() },
      { "unaccounted_s", run.unaccountedS() }, { "user_cpu_s", run.userCpuS },
      { "system_cpu_s", run.systemCpuS }, { "cpu_per_wall", run.cpuPerWall() },
      { "peak_resident_mib",
        run.peakResidentMiB >= 0.0 ? nlohmann::json(run.peakResidentMiB)
                                   : nlohmann::json(nullptr) },
      { "rusage_max_rss_mib", run.maxRssMiB }, { "flagged_as_failure", run.flaggedAsFailure },
      { "timings", run.stages.toJson() } });
    const SpeedBenchmarkRun* base = this->baseOf(run);
    if (!base || base == &run || base->threads == run.threads)
    {
      continue;
    }
    auto entry = [&](const std::string& stage)
    {
      const Scaling k = scaling(*base, run, stage);
      return nlohmann::json{ { "speedup", ratioJson(k.speedup) },
        { "efficiency", ratioJson(k.efficiency) } };
    };
    nlohmann::json stages = nlohmann::json::array();
    for (const StageTimings::Stage& s : run.stages.stages())
    {
      nlohmann::json e = entry(s.name);
      e["name"] = s.name;
      stages.push_back(e);
    }
    scalingJson.push_back(
      { { "frames", run.frames }, { "base_threads", base->threads }, { "threads", run.threads },
        { "total", entry("total") }, { "result", entry("result") }, { "stages", stages } });
  }
  return { { "benchmark", "vimlop evaluate speed" }, { "version", this->version },
    { "commit", this->commit.empty() ? nlohmann::json(nullptr) : nlohmann::json(this->commit) },
    { "program", this->program }, { "ct", this->ctPath }, { "seed", this->seed },
    { "step_mm", this->stepMm > 0.0 ? nlohmann::json(this->stepMm) : nlohmann::json(nullptr) },
    { "upright_deg", this->uprightRollDeg }, { "machine", machineJson }, { "sequences", sequences },
    { "runs", runsJson }, { "scaling", scalingJson }, { "warnings", this->warnings() } };
}

} // namespace vimlop
