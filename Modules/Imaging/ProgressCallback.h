#ifndef vimlop_ProgressCallback_h
#define vimlop_ProgressCallback_h

#include <functional>
#include <string>

namespace vimlop
{

/**
 * @brief Receives the progress of a long computation.
 *
 * `fraction` is the part done, in [0, 1], non-decreasing over one computation;
 * `step` names what is running now (e.g. "connected components"). An empty
 * callback is allowed everywhere one is accepted and means "no reporting".
 * Callbacks run on the calling thread.
 */
using ProgressCallback = std::function<void(double fraction, const std::string& step)>;

/// @brief Calls `progress` when it is set.
inline void reportProgress(
  const ProgressCallback& progress, double fraction, const std::string& step)
{
  if (progress)
  {
    progress(fraction, step);
  }
}

} // namespace vimlop

#endif
