#ifndef vimlop_TerminalEvaluationProgress_h
#define vimlop_TerminalEvaluationProgress_h

#include <vimlop/Evaluation/EvaluationProgress.h>

namespace vimlop
{

/**
 * @brief An EvaluationProgress that writes to stderr: counts as printCount
 * does (one line rewritten on a terminal, a line every tenth of the way in a
 * log), notes as lines. It never cancels.
 */
EvaluationProgress terminalEvaluationProgress();

} // namespace vimlop

#endif
