#ifndef vimlop_StageTimings_h
#define vimlop_StageTimings_h

#include <nlohmann/json.hpp>

#include <chrono>
#include <ctime>
#include <string>
#include <vector>

namespace vimlop
{

/**
 * @brief How long each stage of the main job took: an ordered list of
 * {stage name, wall seconds, process CPU seconds}, in the order the stages
 * ran (VideoRegistrationPipeline::timings(), writeRegistrationOutputs()).
 *
 * Process CPU time counts every thread of the process, so a stage that keeps
 * two threads busy shows about twice its wall time: the ratio says how
 * parallel the stage was. A stage run again replaces its entry (in its
 * place), so that each stage appears once.
 */
class StageTimings
{
public:
  /// @brief One stage: its name (e.g. "sfm"), wall and process CPU time, s.
  struct Stage
  {
    std::string name;
    double wallS = 0.0;
    double cpuS = 0.0;
  };

  /**
   * @brief One moment of the job, e.g. "result_usable" (the registered poses
   * are on disk): its name and when it came, wall seconds on the caller's
   * clock (`vimlop register`: since it started, the clock of its runtime_s).
   */
  struct Mark
  {
    std::string name;
    double atWallS = 0.0;
  };

  /// @brief Measures one stage: wall (steady clock) and process CPU time since its creation.
  class Stopwatch
  {
  public:
    Stopwatch();
    double wallS() const;
    double cpuS() const;

  private:
    std::chrono::steady_clock::time_point WallStart;
    double CpuStartS;
  };

  /**
   * @brief Records stage `name`: appended, or in place of the stage of that
   * name already recorded.
   * @throws vimlop::Error for an empty name or a negative or non-finite time.
   */
  void set(const std::string& name, double wallS, double cpuS);
  /// @brief set() with the times of `watch` so far.
  void set(const std::string& name, const Stopwatch& watch);
  /// @brief Forgets stage `name` (nothing when it was not recorded).
  void remove(const std::string& name);
  /// @brief Records every stage of `other` after (or in place of) these.
  void append(const StageTimings& other);

  /**
   * @brief Records moment `name` at `atWallS`: appended, or in place of the
   * mark of that name already recorded. append() carries marks too.
   * @throws vimlop::Error for an empty name or a negative or non-finite time.
   */
  void mark(const std::string& name, double atWallS);
  /// @brief The mark named `name`, or nullptr when it was not recorded.
  const Mark* findMark(const std::string& name) const;
  const std::vector<Mark>& marks() const { return this->Marks; }

  const std::vector<Stage>& stages() const { return this->Stages; }
  bool empty() const { return this->Stages.empty(); }
  /// @brief The stage named `name`, or nullptr when it was not recorded.
  const Stage* find(const std::string& name) const;
  /// @brief Sums over every stage, s.
  double totalWallS() const;
  double totalCpuS() const;

  /**
   * @brief As JSON: {"stages": [{"name", "wall_s", "cpu_s"}, ...],
   * "total_wall_s", "total_cpu_s"} (the order kept), and when there are
   * marks "marks": [{"name", "at_wall_s"}, ...].
   */
  nlohmann::json toJson() const;
  /**
   * @brief Reads toJson()'s layout back; `source` names it in messages.
   * @throws vimlop::Error when a field is missing or of the wrong type, or a time is negative.
   */
  static StageTimings fromJson(const nlohmann::json& json, const std::string& source);
  /**
   * @brief One line: "stage 1.23 s, ... (total 4.56 s, CPU 7.89 s)", then
   * each mark as "; result_usable at 3.21 s".
   */
  std::string summaryLine() const;

private:
  std::vector<Stage> Stages;
  std::vector<Mark> Marks;
};

} // namespace vimlop

#endif
