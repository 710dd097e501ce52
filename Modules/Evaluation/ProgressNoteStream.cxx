#include <vimlop/Evaluation/ProgressNoteStream.h>

#include <vimlop/Core/Error.h>

namespace vimlop
{

ProgressNoteStream::ProgressNoteStream(const EvaluationProgress& progress)
  : std::ostream(nullptr)
{
  this->Buffer.Progress = progress;
  this->rdbuf(&this->Buffer);
}

int ProgressNoteStream::LineBuffer::overflow(int c)
{
  if (c == traits_type::eof())
  {
    return traits_type::not_eof(c);
  }
  if (c != '\n')
  {
    this->Line.push_back(static_cast<char>(c));
    return c;
  }
  // The stage cannot be stopped from here: the first refusal is kept for
  // throwIfCancelled, and the notes go on.
  if (!this->Progress(this->Line, 0, 0) && this->CancelledAt.empty())
  {
    this->CancelledAt = this->Line;
  }
  this->Line.clear();
  return c;
}

void ProgressNoteStream::throwIfCancelled() const
{
  if (!this->Buffer.CancelledAt.empty())
  {
    throw Error(this->Buffer.CancelledAt + ": cancelled");
  }
}

} // namespace vimlop
