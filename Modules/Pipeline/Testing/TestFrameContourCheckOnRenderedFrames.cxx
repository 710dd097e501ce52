#include <vimlop/Pipeline/FrameContourCheck.h>

#include "RenderedSequence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace vimlop
{
namespace
{

TEST(FrameContourCheck, AgreesAtTheTruePoseAndLessAsThePoseLeavesIt)
{
  // The rendered tube (the model is the surface rendered: ideal world): at
  // each frame's true pose the detected contours lie about a pixel from the
  // model's; moved 1 mm sideways, or turned 2 degrees, the same frame's
  // contours lie farther from them. The check sees a wrong pose that the
  // features (cast from it) cannot.
  const fixtures::Sequence& s = fixtures::sequence();
  const FrameContourCheck check(*s.model, s.intrinsics, cv::Mat());
  int frames = 0;
  double atTruth = 0.0;
  double shifted = 0.0;
  double turned = 0.0;
  for (std::size_t f = 0; f < s.frames.size(); ++f)
  {
    const FrameContourAgreement a = check.check(s.frames[f], s.poses[f]);
    CameraPose aside = s.poses[f];
    aside.centre += aside.rotation.col(0) * 1.0;
    CameraPose twisted = s.poses[f];
    twisted.rotation =
      twisted.rotation * Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).matrix();
    const FrameContourAgreement b = check.check(s.frames[f], aside);
    const FrameContourAgreement c = check.check(s.frames[f], twisted);
    std::printf("frame %2zu: %3d detected, %3d matched: %.2f px at the truth, %.2f px 1 mm "
                "aside, %.2f px turned 2 deg\n",
      f, a.detected, a.matched, a.medianErrorPx, b.medianErrorPx, c.medianErrorPx);
    EXPECT_FALSE(a.modelContours.empty()) << f;
    EXPECT_LE(a.matched, a.detected) << f;
    if (a.matched < 20 || !std::isfinite(b.medianErrorPx) || !std::isfinite(c.medianErrorPx))
    {
      continue;
    }
    ++frames;
    atTruth += a.medianErrorPx;
    shifted += b.medianErrorPx;
    turned += c.medianErrorPx;
  }
  ASSERT_GE(frames, static_cast<int>(s.frames.size()) / 2);
  EXPECT_LT(atTruth / frames, 1.5);
  EXPECT_GT(shifted / frames, atTruth / frames + 1.0);
  EXPECT_GT(turned / frames, atTruth / frames + 1.0);
}

} // namespace
} // namespace vimlop
