#include "OptionLayout.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace
{

struct LayoutEntry
{
  std::string name;
  std::size_t value;
};

#define VIMLOP_LAYOUT_ENTRY(name, value) LayoutEntry{ name, value },

} // namespace

TEST(StableLayout, PublicStructsHaveTheSameLayoutInAProgramBuiltWithAvx2)
{
  // The library is built with the default flags (16-byte SIMD on x86-64); a
  // program built with -mavx2 aligns Eigen's 32-byte types to 32 bytes. Both
  // must lay the public structs out alike.
  const std::vector<LayoutEntry> here = { VIMLOP_OPTION_LAYOUT(VIMLOP_LAYOUT_ENTRY) };
  int count = 0;
  const std::size_t* avx2 = fixtures::optionLayoutWithAvx2(count);
  ASSERT_EQ(count, static_cast<int>(here.size()));
  for (int i = 0; i < count; ++i)
  {
    EXPECT_EQ(avx2[i], here[static_cast<size_t>(i)].value) << here[static_cast<size_t>(i)].name;
  }
}

TEST(StableLayout, UnalignedMatricesComputeLikeAlignedOnes)
{
  vimlop::Matrix2dUnaligned covariance;
  covariance << 4.0, 1.0, 1.0, 2.0;
  const Eigen::Matrix2d aligned = covariance;
  EXPECT_EQ(Eigen::Matrix2d(covariance.inverse()), aligned.inverse());
  EXPECT_EQ(alignof(vimlop::Matrix2dUnaligned), alignof(double));
  EXPECT_EQ(alignof(vimlop::QuaterniondUnaligned), alignof(double));
}
