#include <vimlop/Core/TextFormat.h>

#include <cstdarg>
#include <cstdio>
#include <vector>

namespace vimlop
{

std::string formatText(const char* format, ...)
{
  std::va_list args;
  va_start(args, format);
  std::va_list copy;
  va_copy(copy, args);
  const int length = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  std::vector<char> text(static_cast<size_t>(length > 0 ? length : 0) + 1, '\0');
  std::vsnprintf(text.data(), text.size(), format, args);
  va_end(args);
  return std::string(text.data(), text.size() - 1);
}

} // namespace vimlop
