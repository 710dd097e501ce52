#include <vimlop/Core/TaskPool.h>

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

using namespace vimlop;

TEST(TaskPool, RunsEveryTaskOnce)
{
  for (int threads : { 1, 2, 4 })
  {
    TaskPool pool(threads);
    EXPECT_EQ(pool.threadCount(), threads);
    for (int round = 0; round < 50; ++round)
    {
      std::vector<std::atomic<int>> hits(97);
      pool.run(97, [&](int i) { hits[i]++; });
      for (auto& h : hits)
      {
        ASSERT_EQ(h.load(), 1);
      }
    }
  }
}

TEST(TaskPool, ChunksDependOnlyOnSizes)
{
  TaskPool pool(3);
  std::vector<std::pair<int, int>> chunks(4);
  pool.forChunks(10, 3, [&](int begin, int end) { chunks[begin / 3] = { begin, end }; });
  EXPECT_EQ(chunks, (std::vector<std::pair<int, int>>{ { 0, 3 }, { 3, 6 }, { 6, 9 }, { 9, 10 } }));
}

TEST(TaskPool, PropagatesTheFirstException)
{
  TaskPool pool(2);
  EXPECT_THROW(pool.run(20,
                 [](int i)
                 {
                   if (i == 13)
                   {
                     throw std::runtime_error("task 13 failed");
                   }
                 }),
    std::runtime_error);
  // The pool stays usable.
  std::atomic<int> count{ 0 };
  pool.run(10, [&](int) { count++; });
  EXPECT_EQ(count.load(), 10);
}
