#ifndef vimlop_TerminalProgress_h
#define vimlop_TerminalProgress_h

#include "ProgressCallback.h"

#include <string>

namespace vimlop
{

/**
 * @brief A progress callback that shows "vimlop <command>: 42% <step>" on
 * stderr, rewriting one line, when stderr is a terminal; nothing otherwise
 * (logs and test output stay clean). The line is ended at 100 %.
 */
ProgressCallback terminalProgress(const std::string& command);

} // namespace vimlop

#endif
