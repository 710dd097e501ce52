#include <vimlop/Core/ProcessMemory.h>

#include <gtest/gtest.h>

#include <vector>

namespace vimlop
{
namespace
{

TEST(ProcessMemory, ReadsTheHighWaterMarkOfAStatusText)
{
  EXPECT_DOUBLE_EQ(peakResidentMiBFromStatus(
                     "Name:\tvimlop\nVmPeak:\t 900000 kB\nVmHWM:\t  204800 kB\nVmRSS:\t 1 kB\n"),
    200.0);
  EXPECT_LT(peakResidentMiBFromStatus("Name:\tvimlop\n"), 0.0);
  EXPECT_LT(peakResidentMiBFromStatus("VmHWM:\tmany\n"), 0.0);
}

TEST(ProcessMemory, ThisProcessPeakCoversTheMemoryItTouched)
{
  const double before = peakResidentMiBOfThisProcess();
  ASSERT_GT(before, 0.0);
  // 64 MiB more, every page written so that it is resident.
  std::vector<char> block(64u << 20u, 1);
  const double after = peakResidentMiBOfThisProcess();
  EXPECT_GE(after, before);
  EXPECT_GE(after, 64.0);
  EXPECT_EQ(block[block.size() / 2], 1);
}

} // namespace
} // namespace vimlop
