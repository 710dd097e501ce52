#include <vimlop/Evaluation/EvaluationProgress.h>

#include <vimlop/Core/Error.h>

namespace vimlop
{

void reportEvaluationCount(
  const EvaluationProgress& progress, const std::string& what, int done, int total)
{
  if (progress && !progress(what, done, total))
  {
    throw Error(what + ": cancelled");
  }
}

void reportEvaluationNote(const EvaluationProgress& progress, const std::string& text)
{
  reportEvaluationCount(progress, text, 0, 0);
}

} // namespace vimlop
