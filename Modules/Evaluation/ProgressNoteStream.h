#ifndef vimlop_ProgressNoteStream_h
#define vimlop_ProgressNoteStream_h

#include <vimlop/Evaluation/EvaluationProgress.h>

#include <ostream>
#include <streambuf>
#include <string>

namespace vimlop
{

/**
 * @brief An output stream whose every line becomes a note of an
 * EvaluationProgress: the bridge to stages that log to a std::ostream (the
 * structure from motion). A cancellation asked for while such a stage runs
 * is raised by throwIfCancelled() once the stage returns.
 */
class ProgressNoteStream : public std::ostream
{
public:
  explicit ProgressNoteStream(const EvaluationProgress& progress);

  /// @brief The stream to hand to a stage: this, or null when there is no callback.
  std::ostream* stream() { return this->Buffer.Progress ? this : nullptr; }

  /// @throws vimlop::Error "<last note>: cancelled" when the callback returned false.
  void throwIfCancelled() const;

private:
  struct LineBuffer : std::streambuf
  {
    EvaluationProgress Progress;
    std::string Line;
    std::string CancelledAt;
    int overflow(int c) override;
  };
  LineBuffer Buffer;
};

} // namespace vimlop

#endif
