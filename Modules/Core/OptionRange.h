#ifndef vimlop_OptionRange_h
#define vimlop_OptionRange_h

#include <string>

namespace vimlop
{

/**
 * @brief Checks one setting against its closed range [min, max], as the
 * option tables give it.
 * @throws vimlop::Error "<context>: <key> must lie in [min, max], got <value>"
 *   when `value` is outside the range or not a number.
 */
void requireInRange(
  const std::string& context, const char* key, double value, double min, double max);

} // namespace vimlop

#endif
