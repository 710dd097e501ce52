#include <vimlop/Core/ProcessMemory.h>

#include <fstream>
#include <iterator>
#include <sstream>

namespace vimlop
{

double peakResidentMiBOfThisProcess()
{
  std::ifstream in("/proc/self/status");
  return peakResidentMiBFromStatus(
    std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
}

double peakResidentMiBFromStatus(const std::string& statusText)
{
  std::istringstream in(statusText);
  std::string line;
  while (std::getline(in, line))
  {
    if (line.rfind("VmHWM:", 0) == 0)
    {
      std::istringstream fields(line.substr(6));
      double kib = 0.0;
      std::string unit;
      if (fields >> kib >> unit && unit == "kB" && kib >= 0.0)
      {
        return kib / 1024.0;
      }
      return -1.0;
    }
  }
  return -1.0;
}

} // namespace vimlop
