#include <vimlop/Evaluation/SpeedBenchmark.h>

#include <vimlop/Core/ChildProcess.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <sstream>

#include <unistd.h>

namespace vimlop
{

namespace fs = std::filesystem;

namespace
{

std::string readText(const fs::path& path)
{
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// The last non-empty line of a child's stderr: its error message, usually.
std::string lastLine(const fs::path& path)
{
  std::istringstream in(readText(path));
  std::string line;
  std::string last;
  while (std::getline(in, line))
  {
    if (line.find_first_not_of(" \t\r") != std::string::npos)
    {
      last = line;
    }
  }
  return last;
}

void checkCounts(
  const std::vector<int>& counts, const char* flag, const char* what, int least, int most)
{
  if (counts.empty())
  {
    throw Error(formatText("speed benchmark: %s: give at least one %s", flag, what));
  }
  for (size_t i = 0; i < counts.size(); ++i)
  {
    if (counts[i] < least || counts[i] > most)
    {
      throw Error(formatText("speed benchmark: %s: each %s must be from %d to %d, got %d", flag,
        what, least, most, counts[i]));
    }
    if (std::find(counts.begin(), counts.begin() + i, counts[i]) != counts.begin() + i)
    {
      throw Error(formatText("speed benchmark: %s: %d is listed twice", flag, counts[i]));
    }
  }
}

/// Runs one child; refuses any exit code but those in `accepted`.
ChildProcessResult runStep(const std::vector<std::string>& arguments, const fs::path& out,
  const fs::path& err, const std::string& what, std::initializer_list<int> accepted)
{
  const ChildProcessResult r = runChildProcess(arguments, out.string(), err.string());
  if (std::find(accepted.begin(), accepted.end(), r.exitCode) == accepted.end())
  {
    const std::string how = r.signal != 0 ? formatText("was killed by signal %d", r.signal)
                                          : formatText("failed with exit code %d", r.exitCode);
    const std::string said = lastLine(err);
    throw Error(what + " " + how + (said.empty() ? std::string() : ": " + said) + " (see '" +
      err.string() + "')");
  }
  return r;
}

} // namespace

void SpeedBenchmarkOptions::validate() const
{
  if (this->ctPath.empty())
  {
    throw Error("speed benchmark: give the CT (--ct)");
  }
  if (this->workFolder.empty())
  {
    throw Error("speed benchmark: no work folder given");
  }
  checkCounts(this->frameCounts, "--frames", "frame count", 2, 10000);
  checkCounts(this->threadCounts, "--threads", "thread count", 1, 1024);
  if (!(this->stepMm >= 0.0) || !std::isfinite(this->stepMm))
  {
    throw Error(formatText("speed benchmark: --step-mm: must be zero (simulate's default) or "
                           "positive, got %g",
      this->stepMm));
  }
  if (!(this->uprightRollDeg <= 180.0))
  {
    throw Error(formatText("speed benchmark: --upright-deg: must be at most 180 (negative: any "
                           "roll), got %g",
      this->uprightRollDeg));
  }
}

std::vector<int> SpeedBenchmarkOptions::parseCounts(
  const std::string& text, const std::string& what)
{
  std::vector<int> counts;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
  {
    size_t used = 0;
    long value = 0;
    try
    {
      value = std::stol(item, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (item.empty() || used != item.size() || value < -1000000 || value > 1000000)
    {
      throw Error(what + ": expected whole numbers separated by commas, got '" + text + "'");
    }
    counts.push_back(static_cast<int>(value));
  }
  if (counts.empty() || (!text.empty() && text.back() == ','))
  {
    throw Error(what + ": expected whole numbers separated by commas, got '" + text + "'");
  }
  return counts;
}

SpeedBenchmarkReport runSpeedBenchmark(const SpeedBenchmarkOptions& o, std::ostream* progress)
{
  o.validate();
  // /proc/self/exe itself, not the path it names: in the child it is still
  // this program's file even if a build replaces the file at that path meanwhile.
  const std::string program = o.executable.empty() ? "/proc/self/exe" : o.executable;
  auto say = [&](const std::string& text)
  {
    if (progress)
    {
      *progress << "vimlop evaluate speed: " << text << std::endl;
    }
  };
  const fs::path work(o.workFolder);
  std::error_code ec;
  fs::create_directories(work, ec);
  if (ec)
  {
    throwFileError(work.string(), "cannot create the work folder (" + ec.message() + ")");
  }
  SpeedBenchmarkReport report;
  report.program = o.executable.empty() ? currentExecutablePath() : o.executable;
  report.ctPath = o.ctPath;
  report.seed = o.seed;
  report.stepMm = o.stepMm;
  report.uprightRollDeg = o.uprightRollDeg;
  report.machine = MachineDescription::ofThisMachine();
  auto sequenceOf = [&](int frames) { return work / formatText("sequence-%d", frames); };
  for (int frames : o.frameCounts)
  {
    const fs::path sequence = sequenceOf(frames);
    fs::remove_all(sequence, ec);
    say(formatText(
      "simulating %d frames (seed %llu)", frames, static_cast<unsigned long long>(o.seed)));
    std::vector<std::string> simulate = { program, "simulate", "--ct", o.ctPath, "--frames",
      std::to_string(frames), "--seed", std::to_string(o.seed), "--out", sequence.string() };
    if (o.stepMm > 0.0)
    {
      simulate.insert(simulate.end(), { "--step-mm", formatText("%.17g", o.stepMm) });
    }
    simulate.insert(simulate.end(), { "--upright-deg", formatText("%.17g", o.uprightRollDeg) });
    ChildProcessResult simulated;
    try
    {
      simulated = runStep(simulate, work / formatText("simulate-%d.out", frames),
        work / formatText("simulate-%d.err", frames),
        formatText("vimlop simulate (%d frames)", frames), { 0 });
    }
    catch (const Error& e)
    {
      // The usual cause: the path of a long sequence is longer than any straight passage.
      throw Error(std::string(e.what()) +
        (o.stepMm > 0.0 ? "" : "; a long sequence may need a shorter --step-mm (e.g. 0.2)"));
    }
    report.simulateWallS.emplace_back(frames, simulated.wallS);
  }
  for (int frames : o.frameCounts)
  {
    const fs::path sequence = sequenceOf(frames);
    for (int threads : o.threadCounts)
    {
      const std::string name = formatText("register-%d-t%d", frames, threads);
      const std::string label =
        formatText("%d frames, %d thread%s", frames, threads, threads == 1 ? "" : "s");
      say(label + ": registering");
      const fs::path out = work / (name + ".json");
      // Exit code 3: the result is flagged as a failure, but it was written and timed.
      const ChildProcessResult r =
        runStep({ program, "register", "--ct", o.ctPath, "--frames", (sequence / "frames").string(),
                  "--intrinsics", (sequence / "intrinsics.yaml").string(), "--tracker",
                  (sequence / "tracker.csv").string(), "--init", "canonical", "--threads",
                  std::to_string(threads), "--json", "--force", "--out", (work / name).string() },
          out, work / (name + ".err"),
          formatText("vimlop register (%d frames, %d threads)", frames, threads), { 0, 3 });
      nlohmann::json summary;
      try
      {
        summary = nlohmann::json::parse(readText(out));
      }
      catch (const nlohmann::json::exception& e)
      {
        throw Error(
          "'" + out.string() + "': not the JSON summary of vimlop register (" + e.what() + ")");
      }
      if (!summary.is_object() || !summary.contains("timings"))
      {
        throwFileError(out.string(), "the summary has no \"timings\"");
      }
      SpeedBenchmarkRun run;
      run.frames = frames;
      run.threads = threads;
      run.wallS = r.wallS;
      run.userCpuS = r.userCpuS;
      run.systemCpuS = r.systemCpuS;
      run.maxRssMiB = r.peakResidentMiB;
      if (summary.contains("peak_resident_mib") && summary.at("peak_resident_mib").is_number())
      {
        run.peakResidentMiB = summary.at("peak_resident_mib").get<double>();
      }
      run.stages = StageTimings::fromJson(summary.at("timings"), out.string());
      run.flaggedAsFailure = r.exitCode == 3;
      if (run.stages.totalWallS() > run.wallS)
      {
        throw Error(formatText("'%s': the stages took %.3f s, more than the %.3f s the whole "
                               "run took: the timings are wrong",
          out.string().c_str(), run.stages.totalWallS(), run.wallS));
      }
      say(formatText("%s: %.1f s (result after %.1f s), peak %.0f MiB%s", label.c_str(), run.wallS,
        run.resultS(), run.peakResidentMiB, run.flaggedAsFailure ? ", flagged as a failure" : ""));
      report.runs.push_back(std::move(run));
    }
  }
  report.loadAverageEnd = MachineDescription::ofThisMachine().loadAverage;
  return report;
}

std::string sourceCommit(const std::string& sourceFolder)
{
  if (sourceFolder.empty() || !fs::exists(fs::path(sourceFolder) / ".git"))
  {
    return std::string();
  }
  const fs::path out = fs::temp_directory_path() / formatText("vimlop-commit-%d.txt", ::getpid());
  std::string commit;
  try
  {
    const ChildProcessResult r = runChildProcess(
      { "git", "-C", sourceFolder, "describe", "--always", "--dirty", "--abbrev=12" }, out.string(),
      "/dev/null");
    if (r.exitCode == 0)
    {
      commit = lastLine(out);
    }
  }
  catch (const Error&)
  {
    // No git: the commit stays unknown.
  }
  std::error_code ec;
  fs::remove(out, ec);
  return commit;
}

} // namespace vimlop
