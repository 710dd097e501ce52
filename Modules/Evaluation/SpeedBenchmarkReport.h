#ifndef vimlop_SpeedBenchmarkReport_h
#define vimlop_SpeedBenchmarkReport_h

#include <vimlop/Evaluation/MachineDescription.h>
#include <vimlop/Pipeline/StageTimings.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief One run of the main job in `vimlop evaluate speed`: one sequence, one thread count.
struct SpeedBenchmarkRun
{
  int frames = 0;
  int threads = 0;
  /// The child process's wall time (start to exit, by the parent's clock), s.
  double wallS = 0.0;
  /// Its user and system CPU time (every thread), s.
  double userCpuS = 0.0;
  double systemCpuS = 0.0;
  /// Its peak resident memory, MiB: its own address space's high-water mark
  /// (VmHWM, as `vimlop register --json` reports it), -1 when unknown.
  double peakResidentMiB = -1.0;
  /// wait4()'s ru_maxrss, MiB: at least the parent's peak at the spawn too,
  /// since Linux carries it across exec (ProcessMemory.h); an upper bound.
  double maxRssMiB = 0.0;
  /// Its stages as `vimlop register --json` timed them, in order.
  StageTimings stages;
  /// The registration was flagged as a failure (exit code 3): timed all the same.
  bool flaggedAsFailure = false;

  /// @brief True for the stages that write the result down (the record and
  /// the files: poses, pictures, video, camera path, result.json, report).
  static bool isOutputStage(const std::string& name);
  /// @brief Time until the result is usable, s: the run's "result_usable"
  /// mark (the registered poses on disk, since the child started) when it
  /// has one, else (runs of builds before the mark) every stage before the outputs.
  double resultS() const;
  /// @brief The output stages' time (record, poses, pictures, ..., report), s.
  double outputsS() const;
  /// @brief (user + system CPU) / wall: about the thread count when the run
  /// had its processors to itself and kept them busy, less when it waited.
  double cpuPerWall() const;
  /// @brief The wall time no stage covers (start-up, reading the small files, exit), s.
  double unaccountedS() const;
};

/**
 * @brief What `vimlop evaluate speed` measured: the machine, the runs
 * (frames x threads) and the thread scaling of each stage; its table and its
 * JSON (layout in Documentation/SpeedBenchmark.md).
 *
 * Thread scaling compares each run with the run of the same sequence on the
 * fewest threads (the base): speed-up = base wall / run wall, parallel
 * efficiency = speed-up x base threads / run threads (1: perfect scaling).
 */
class SpeedBenchmarkReport
{
public:
  /// @brief The thread scaling of one stage (or the total) between two runs.
  struct Scaling
  {
    /// base wall / run wall; empty when either took no measurable time.
    std::optional<double> speedup;
    std::optional<double> efficiency;
  };

  std::string version;
  /// The source tree's commit (git describe), empty when unknown.
  std::string commit;
  /// The program that ran as the children (its path).
  std::string program;
  std::string ctPath;
  std::uint64_t seed = 1;
  /// The simulation's step per frame, mm (0: simulate's default).
  double stepMm = 0.0;
  /// The scope's largest roll from upright, deg (negative: any).
  double uprightRollDeg = 10.0;
  /// The machine when the benchmark started, and its load average at the end.
  MachineDescription machine;
  std::array<double, 3> loadAverageEnd{ -1.0, -1.0, -1.0 };
  /// Per sequence, the wall time of `vimlop simulate` (not part of the main job), s.
  std::vector<std::pair<int, double>> simulateWallS;
  std::vector<SpeedBenchmarkRun> runs;

  /// @brief The scaling of `stage` ("total", "result" or a stage's name) from `base` to `run`.
  static Scaling scaling(
    const SpeedBenchmarkRun& base, const SpeedBenchmarkRun& run, const std::string& stage);
  /// @brief Every stage any run timed, in the order they ran.
  std::vector<std::string> stageNames() const;
  /// @brief The run of the same sequence on the fewest threads (nullptr when none).
  const SpeedBenchmarkRun* baseOf(const SpeedBenchmarkRun& run) const;

  /// @brief One row per run: frames, threads, wall, result, each stage (s),
  /// CPU per wall, peak MiB.
  std::vector<std::string> tableLines() const;
  /// @brief Per run on more threads than its base: the speed-up and efficiency of the total,
  /// the result and each stage.
  std::vector<std::string> scalingLines() const;
  /**
   * @brief What makes the figures doubtful: a load average at the start or
   * the end at least the number of processors, a 1-thread run that had its
   * processor less than 80 % of its wall time.
   */
  std::vector<std::string> warnings() const;
  nlohmann::json toJson() const;
};

} // namespace vimlop

#endif
