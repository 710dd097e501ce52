#ifndef vimlop_TeeStream_h
#define vimlop_TeeStream_h

#include <ostream>
#include <streambuf>

namespace vimlop
{

/**
 * @brief An output stream that writes everything to two others: e.g. a
 * run's progress lines to the terminal and to the log file of its result
 * folder. Flushing it flushes both.
 */
class TeeStream : public std::ostream
{
public:
  TeeStream(std::ostream& first, std::ostream& second);

private:
  struct Both : std::streambuf
  {
    Both(std::ostream& first, std::ostream& second)
      : First(first)
      , Second(second)
    {
    }
    int overflow(int c) override;
    std::streamsize xsputn(const char* text, std::streamsize count) override;
    int sync() override;
    std::ostream& First;
    std::ostream& Second;
  };
  Both Buffer;
};

} // namespace vimlop

#endif
