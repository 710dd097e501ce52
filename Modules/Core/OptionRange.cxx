#include <vimlop/Core/OptionRange.h>

#include <vimlop/Core/Error.h>

#include <sstream>

namespace vimlop
{

void requireInRange(
  const std::string& context, const char* key, double value, double min, double max)
{
  // Written so that NaN fails too.
  if (!(value >= min && value <= max))
  {
    std::ostringstream message;
    message << context << ": " << key << " must lie in [" << min << ", " << max << "], got "
            << value;
    throw Error(message.str());
  }
}

} // namespace vimlop
