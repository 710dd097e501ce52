#include "TerminalEvaluationProgress.h"

#include "TerminalProgress.h"

#include <iostream>

namespace vimlop
{

EvaluationProgress terminalEvaluationProgress()
{
  return [](const std::string& what, int done, int total)
  {
    if (total > 0)
    {
      printCount(&std::cerr, what, done, total);
    }
    else
    {
      std::cerr << what << "\n";
    }
    return true;
  };
}

} // namespace vimlop
