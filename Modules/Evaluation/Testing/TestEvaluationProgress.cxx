#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/EvaluationProgress.h>
#include <vimlop/Evaluation/ProgressNoteStream.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace vimlop;

TEST(EvaluationProgress, PassesCountsAndNotesAndCancelsWithTheirName)
{
  std::vector<std::string> seen;
  bool go = true;
  const EvaluationProgress progress = [&](const std::string& what, int done, int total)
  {
    seen.push_back(what + " " + std::to_string(done) + "/" + std::to_string(total));
    return go;
  };
  reportEvaluationCount(progress, "P1: trial", 2, 5);
  reportEvaluationNote(progress, "P2: SfM done");
  reportEvaluationCount(EvaluationProgress(), "nobody listens", 1, 1);
  EXPECT_EQ(seen, (std::vector<std::string>{ "P1: trial 2/5", "P2: SfM done 0/0" }));
  go = false;
  try
  {
    reportEvaluationCount(progress, "P3: run", 1, 2);
    FAIL() << "no cancellation";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "P3: run: cancelled");
  }
}

TEST(ProgressNoteStream, TurnsEveryLineIntoANoteAndRaisesACancellationAfterwards)
{
  std::vector<std::string> notes;
  ProgressNoteStream stream(
    [&](const std::string& what, int, int total)
    {
      EXPECT_EQ(total, 0);
      notes.push_back(what);
      return what != "sfm: stop here";
    });
  ASSERT_NE(stream.stream(), nullptr);
  *stream.stream() << "sfm: " << 12 << " frames\nsfm: stop here\nsfm: after";
  EXPECT_EQ(notes, (std::vector<std::string>{ "sfm: 12 frames", "sfm: stop here" }));
  try
  {
    stream.throwIfCancelled();
    FAIL() << "no cancellation";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "sfm: stop here: cancelled");
  }
  ProgressNoteStream silent{ EvaluationProgress() };
  EXPECT_EQ(silent.stream(), nullptr);
  EXPECT_NO_THROW(silent.throwIfCancelled());
}
