#include <vimlop/Cohort/VirtualDisplay.h>

#include <vimlop/Core/ChildProcess.h>
#include <vimlop/Core/Error.h>

#include <cstdlib>

namespace vimlop
{

VirtualDisplay::VirtualDisplay(double timeoutS)
{
  // The number comes on its stdout, with a newline, once it accepts clients.
  this->Server =
    std::make_unique<ChildProcess>(std::vector<std::string>{ "Xvfb", "-displayfd", "1", "-screen",
                                     "0", "1280x1024x24", "-nolisten", "tcp", "-noreset" },
      true);
  std::string number;
  char c = 0;
  try
  {
    while (this->Server->read(&c, 1, timeoutS) == 1 && c != '\n')
    {
      number += c;
    }
  }
  catch (const Error&)
  {
    this->Server->finish(true);
    throw Error("Xvfb did not answer in " + std::to_string(static_cast<int>(timeoutS)) + " s");
  }
  if (number.empty() || number.find_first_not_of("0123456789") != std::string::npos)
  {
    this->Server->finish(true);
    std::string said = this->Server->errorOutput();
    while (!said.empty() && said.back() == '\n')
    {
      said.pop_back();
    }
    const size_t lastLine = said.rfind('\n');
    throw Error(
      "Xvfb did not start" + (said.empty() ? std::string() : ": " + said.substr(lastLine + 1)));
  }
  this->Name = ":" + number;
  ::setenv("DISPLAY", this->Name.c_str(), 1);
}

VirtualDisplay::~VirtualDisplay()
{
  ::unsetenv("DISPLAY");
  this->Server.reset(); // killed and reaped
}

} // namespace vimlop
