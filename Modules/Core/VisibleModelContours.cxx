#include <vimlop/Core/VisibleModelContours.h>

#include <vimlop/Core/RegistrationResult.h>

#include <chrono>

namespace vimlop
{

std::vector<ModelContourPoint> visibleModelContours(const RegistrationModel& model,
  const PinholeCamera& intrinsics, const CameraPose& cameraToCT,
  const OccludingContourOptions& options, StageTimes* times)
{
  using Clock = std::chrono::steady_clock;
  auto start = Clock::now();
  std::vector<ModelContourPoint> samples =
    extractOccludingContours(model.mesh(), intrinsics, cameraToCT, options);
  const auto extracted = Clock::now();

  std::vector<Eigen::Vector3d> points(samples.size());
  for (size_t i = 0; i < samples.size(); ++i)
  {
    points[i] = samples[i].point;
  }
  std::vector<char> visible;
  model.visibility().classify(intrinsics, cameraToCT, points, visible);
  std::vector<ModelContourPoint> kept;
  for (size_t i = 0; i < samples.size(); ++i)
  {
    if (visible[i])
    {
      kept.push_back(samples[i]);
    }
  }
  if (times)
  {
    times->contoursMs += std::chrono::duration<double, std::milli>(extracted - start).count();
    times->visibilityMs +=
      std::chrono::duration<double, std::milli>(Clock::now() - extracted).count();
  }
  return kept;
}

} // namespace vimlop
