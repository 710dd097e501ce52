#include "TerminalProgress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

namespace vimlop
{

ProgressCallback terminalProgress(const std::string& command)
{
  if (!isatty(fileno(stderr)))
  {
    return ProgressCallback();
  }
  // Shared state: the callback is copied into std::function objects.
  struct State
  {
    int lastPercent = -1;
    std::string lastStep;
  };
  auto state = std::make_shared<State>();
  return [command, state](double fraction, const std::string& step)
  {
    const int percent = static_cast<int>(std::floor(100.0 * std::clamp(fraction, 0.0, 1.0)));
    if (percent == state->lastPercent && step == state->lastStep)
    {
      return;
    }
    state->lastPercent = percent;
    state->lastStep = step;
    // \r and clear-to-end-of-line: one line that updates in place.
    std::fprintf(stderr, "\rvimlop %s: %3d%% %s\033[K", command.c_str(), percent, step.c_str());
    if (percent >= 100)
    {
      std::fprintf(stderr, "\n");
    }
    std::fflush(stderr);
  };
}

void printCount(std::ostream* out, const std::string& label, int done, int total)
{
  if (!out)
  {
    return;
  }
  const bool terminal =
    (out == &std::cerr && isatty(fileno(stderr))) || (out == &std::cout && isatty(fileno(stdout)));
  if (terminal)
  {
    *out << "\r" << label << " " << done << "/" << total << (done >= total ? "\n" : "")
         << std::flush;
    return;
  }
  const int step = std::max(1, total / 10);
  if (done % step == 0 || done >= total)
  {
    *out << label << " " << done << "/" << total << "\n" << std::flush;
  }
}

} // namespace vimlop
