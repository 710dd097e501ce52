#ifndef vimlop_ErrorMessage_h
#define vimlop_ErrorMessage_h

// The message a test expects of a refused input.

#include <vimlop/Core/Error.h>

#include <functional>
#include <string>

namespace vimlop::fixtures
{

/// @brief The message of the vimlop::Error that `action` throws, or "no error".
inline std::string errorMessageOf(const std::function<void()>& action)
{
  try
  {
    action();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "no error";
}

} // namespace vimlop::fixtures

#endif
