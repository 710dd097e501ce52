#ifndef vimlop_SpeedBenchmark_h
#define vimlop_SpeedBenchmark_h

#include <vimlop/Evaluation/SpeedBenchmarkReport.h>

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief Settings of the main job's speed benchmark (`vimlop evaluate speed`,
 * issue 22): which sequences, on how many threads, and where.
 */
struct SpeedBenchmarkOptions
{
  /// The CT: the simulated world's anatomy and the CT `vimlop register` reads (required).
  std::string ctPath;
  /// The sequences' lengths, frames (default 6, 30, 60, 100: P1's 6 frames,
  /// the demo's 30, and two longer sequences, issue 22). Each 2-10000, as
  /// `vimlop simulate` accepts.
  std::vector<int> frameCounts{ 6, 30, 60, 100 };
  /// The thread counts each sequence is registered with (default 1, 2: the
  /// scaling on the 2-core machines the project runs on). Each 1-1024 (0,
  /// "every core", would hide the count measured).
  std::vector<int> threadCounts{ 1, 2 };
  /// The simulation's seed (default 1, the CLI tests' sequence).
  std::uint64_t seed = 1;
  /// The simulated endoscope's advance per frame, mm (default 0: `vimlop
  /// simulate`'s own, 0.5 mm). The path is about (frames + 15) x this long
  /// and must fit in a straight passage: in the bundled CT 30 frames fit at
  /// 0.5 mm and 60 do not (37.5 mm), so longer sequences need a shorter step
  /// (0.2 mm: 100 frames in 23 mm). Zero or positive, finite.
  double stepMm = 0.0;
  /// The scope is held upright within this many degrees (default 10, the
  /// demo's): a freely rolled scope (negative) fails from canonical poses
  /// (issue 15), and the job to time is the one that succeeds. At most 180.
  double uprightRollDeg = 10.0;
  /// Where the sequences and results go (required; the caller makes and removes it).
  std::string workFolder;
  /// The `vimlop` program run as a child (default: empty, this program:
  /// /proc/self/exe, which stays this program's file even when a build
  /// replaces the file at its path during the benchmark).
  std::string executable;

  /**
   * @brief Checks the settings.
   * @throws vimlop::Error naming the first problem: no CT or work folder,
   * no or a repeated or out-of-range frame or thread count, a negative step.
   */
  void validate() const;
  /**
   * @brief "6,30,60" as whole numbers; `what` names the flag in messages.
   * @throws vimlop::Error for an empty item or one that is not a whole number.
   */
  static std::vector<int> parseCounts(const std::string& text, const std::string& what);
};

/**
 * @brief Runs the benchmark: first, for each frame count, `vimlop simulate
 * --frames N --seed S [--step-mm D]` (the ideal world) into the work folder
 * (so that a sequence the airway cannot hold fails before the long work),
 * then for each sequence and thread count `vimlop register` on the simulated user files as a user
 * would (the CT, frames, intrinsics and tracker; canonical starts; default outputs;
 * `--threads T --json`), each a child process timed by wall clock and wait4()
 * (peak memory, CPU), with the stages it reports. Progress lines go to
 * `progress` (none when null).
 * @throws vimlop::Error for invalid options, or when a child fails (its
 * exit code and the last line it wrote to stderr).
 */
SpeedBenchmarkReport runSpeedBenchmark(
  const SpeedBenchmarkOptions& options, std::ostream* progress);

/// @brief `git describe --always --dirty` of `sourceFolder`, or "" when git or the tree is absent.
std::string sourceCommit(const std::string& sourceFolder);

} // namespace vimlop

#endif
