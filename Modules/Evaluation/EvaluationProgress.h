#ifndef vimlop_EvaluationProgress_h
#define vimlop_EvaluationProgress_h

#include <functional>
#include <string>

namespace vimlop
{

/**
 * @brief Receives the progress of an evaluation protocol: `done` of `total`
 * steps of `what` (e.g. "P1: trial", 3, 100), or, with `total` 0, a note
 * `what` on how a stage went (e.g. the SfM summary of P2). Return false to
 * cancel: the protocol then throws vimlop::Error ("...: cancelled").
 *
 * An empty callback is allowed everywhere one is accepted and means "no
 * reporting". Protocols that run work in parallel call it from one thread
 * at a time.
 */
using EvaluationProgress = std::function<bool(const std::string& what, int done, int total)>;

/**
 * @brief Reports `done` of `total` steps of `what` to `progress` when it is set.
 * @throws vimlop::Error "<what>: cancelled" when the callback returns false.
 */
void reportEvaluationCount(
  const EvaluationProgress& progress, const std::string& what, int done, int total);

/**
 * @brief Reports the note `text` (total 0) to `progress` when it is set.
 * @throws vimlop::Error "<text>: cancelled" when the callback returns false.
 */
void reportEvaluationNote(const EvaluationProgress& progress, const std::string& text);

} // namespace vimlop

#endif
