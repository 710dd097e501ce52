#ifndef vimlop_MachineDescription_h
#define vimlop_MachineDescription_h

#include <nlohmann/json.hpp>

#include <array>
#include <string>

namespace vimlop
{

/**
 * @brief What a timing depends on besides the code: the machine's processor,
 * how many threads it runs at once and how busy it was (the load average),
 * as `vimlop evaluate speed` records them beside its figures.
 */
struct MachineDescription
{
  /// The processor's model name (/proc/cpuinfo), empty when unknown.
  std::string cpuModel;
  /// Logical processors (std::thread::hardware_concurrency), 0 when unknown.
  int logicalCpus = 0;
  /// The 1-, 5- and 15-minute load averages (/proc/loadavg), -1 when unknown.
  std::array<double, 3> loadAverage{ -1.0, -1.0, -1.0 };

  /// @brief This machine, now (unknown fields when /proc cannot be read).
  static MachineDescription ofThisMachine();
  /// @brief The first "model name" of a /proc/cpuinfo text, or "" when it has none.
  static std::string cpuModelFromCpuinfo(const std::string& text);
  /**
   * @brief The three load averages that begin a /proc/loadavg text.
   * @throws vimlop::Error when it does not begin with three non-negative numbers.
   */
  static std::array<double, 3> loadAverageFromText(const std::string& text);
  /// @brief {"cpu_model", "logical_cpus", "load_average"} (null for what is unknown).
  nlohmann::json toJson() const;
};

} // namespace vimlop

#endif
