#include <vimlop/Evaluation/MachineDescription.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

namespace vimlop
{

namespace
{

std::string readText(const char* path)
{
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace

MachineDescription MachineDescription::ofThisMachine()
{
  MachineDescription m;
  m.cpuModel = cpuModelFromCpuinfo(readText("/proc/cpuinfo"));
  m.logicalCpus = static_cast<int>(std::thread::hardware_concurrency());
  try
  {
    m.loadAverage = loadAverageFromText(readText("/proc/loadavg"));
  }
  catch (const Error&)
  {
    // Not Linux, or no /proc: the load stays unknown (-1).
  }
  return m;
}

std::string MachineDescription::cpuModelFromCpuinfo(const std::string& text)
{
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
  {
    const size_t colon = line.find(':');
    if (colon != std::string::npos && trimmed(line.substr(0, colon)) == "model name")
    {
      return trimmed(line.substr(colon + 1));
    }
  }
  return std::string();
}

std::array<double, 3> MachineDescription::loadAverageFromText(const std::string& text)
{
  std::istringstream in(text);
  std::array<double, 3> load{};
  for (double& l : load)
  {
    if (!(in >> l) || !(l >= 0.0))
    {
      throw Error("load average: expected three non-negative numbers, got '" +
        trimmed(text.substr(0, 40)) + "'");
    }
  }
  return load;
}

nlohmann::json MachineDescription::toJson() const
{
  nlohmann::json j = { { "cpu_model", nullptr }, { "logical_cpus", nullptr },
    { "load_average", nullptr } };
  if (!this->cpuModel.empty())
  {
    j["cpu_model"] = this->cpuModel;
  }
  if (this->logicalCpus > 0)
  {
    j["logical_cpus"] = this->logicalCpus;
  }
  if (this->loadAverage[0] >= 0.0)
  {
    j["load_average"] = this->loadAverage;
  }
  return j;
}

} // namespace vimlop
