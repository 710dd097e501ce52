#include <vimlop/Pipeline/VideoRegistrationPipeline.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Pipeline/RegistrationOutputs.h>

#include <gtest/gtest.h>

namespace vimlop
{
namespace
{

TEST(VideoRegistrationPipelineOptions, AreTheProductionDefaultsForVideo)
{
  const VideoRegistrationOptions o;
  // The paper's values for contours detected in video (Σ2d = 1 px², κ = 200)
  // and the stall rule of a registration with thousands of contour points.
  EXPECT_DOUBLE_EQ(o.registration.contourMatch.positionCovariancePx2(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(o.registration.contourMatch.kappa, 200.0);
  EXPECT_DOUBLE_EQ(o.registration.stallRelativeDecrease, 1e-5);
  EXPECT_EQ(o.registration.stallIterations, 10);
  EXPECT_EQ(o.registration.maxIterations, 300);
  EXPECT_DOUBLE_EQ(o.scaleBoundFactor, 1.25);
}

TEST(VideoRegistrationPipelineOptions, GiveScaleBoundsAroundTheInitialScale)
{
  VideoRegistrationOptions o;
  o.registration.threads = 1;
  const RegistrationOptions r = o.registrationOptions(2.0);
  EXPECT_DOUBLE_EQ(r.minScale, 1.6);
  EXPECT_DOUBLE_EQ(r.maxScale, 2.5);
  EXPECT_EQ(r.threads, 1);
}

TEST(VideoRegistrationPipelineOptions, AScaleBoundOfOneIsAnError)
{
  VideoRegistrationOptions o;
  o.scaleBoundFactor = 1.0;
  try
  {
    VideoRegistrationPipeline pipeline(o);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(
      e.what(), "video registration options: scale_bound_factor must lie in [1.0001, 10], got 1");
  }
}

TEST(VideoRegistrationPipeline, StagesOutOfOrderSayWhatMustComeFirst)
{
  VideoRegistrationPipeline pipeline;
  try
  {
    pipeline.makeData();
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "video registration: reconstruct first");
  }
  EXPECT_THROW(pipeline.run(), Error);
  EXPECT_THROW(pipeline.detectContours(), Error);
}

TEST(VideoRegistrationPipelineOptions, AreWrittenAsJsonWithTheRegistrationOptions)
{
  const nlohmann::json j = registrationOptionsJson(VideoRegistrationOptions());
  EXPECT_EQ(j["registration"]["max_iterations"].get<int>(), 300);
  EXPECT_DOUBLE_EQ(j["scale_bound_factor"].get<double>(), 1.25);
  EXPECT_EQ(j["scale_factors"].size(), 3u);
  EXPECT_DOUBLE_EQ(j["failure_threshold_px"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(j["failure_residual_mm"].get<double>(), 0.8);
}

} // namespace
} // namespace vimlop
