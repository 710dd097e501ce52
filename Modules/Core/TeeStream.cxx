#include <vimlop/Core/TeeStream.h>

namespace vimlop
{

// The buffer is a member, built after std::ostream's constructor: the stream
// gets it with rdbuf() once it exists.
TeeStream::TeeStream(std::ostream& first, std::ostream& second)
  : std::ostream(nullptr)
  , Buffer(first, second)
{
  this->rdbuf(&this->Buffer);
}

int TeeStream::Both::overflow(int c)
{
  if (c == traits_type::eof())
  {
    return traits_type::not_eof(c);
  }
  const char character = traits_type::to_char_type(c);
  this->First.put(character);
  this->Second.put(character);
  return c;
}

std::streamsize TeeStream::Both::xsputn(const char* text, std::streamsize count)
{
  this->First.write(text, count);
  this->Second.write(text, count);
  return count;
}

int TeeStream::Both::sync()
{
  this->First.flush();
  this->Second.flush();
  return this->First && this->Second ? 0 : -1;
}

} // namespace vimlop
