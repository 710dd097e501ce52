#ifndef vimlop_TerminalProgress_h
#define vimlop_TerminalProgress_h

#include <vimlop/Imaging/ProgressCallback.h>

#include <iosfwd>
#include <string>

namespace vimlop
{

/**
 * @brief A progress callback that shows "vimlop <command>: 42% <step>" on
 * stderr, rewriting one line, when stderr is a terminal; nothing otherwise
 * (logs and test output stay clean). The line is ended at 100 %.
 */
ProgressCallback terminalProgress(const std::string& command);

/**
 * @brief Reports `done` of `total` steps as "<label> <done>/<total>" on
 * `out` (nothing when null): one line rewritten in place when `out` is
 * std::cerr or std::cout on a terminal, ended at the last step; otherwise a
 * line at every tenth of the way, so that a log keeps a readable trace.
 */
void printCount(std::ostream* out, const std::string& label, int done, int total);

} // namespace vimlop

#endif
