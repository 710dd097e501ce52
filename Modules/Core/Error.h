#ifndef vimlop_Error_h
#define vimlop_Error_h

#include <stdexcept>
#include <string>

namespace vimlop
{

/**
 * @brief The exception VIMLOP throws for input it cannot work with.
 *
 * The message is meant for the user: it names the offending input and the
 * problem in one line (e.g. "mesh has no faces"). The command-line program
 * prints it as is and exits with a non-zero code.
 */
class Error : public std::runtime_error
{
public:
  explicit Error(const std::string& message)
    : std::runtime_error(message)
  {
  }
};

} // namespace vimlop

#endif
