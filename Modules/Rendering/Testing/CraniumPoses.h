#ifndef vimlop_CraniumPoses_h
#define vimlop_CraniumPoses_h

// Camera poses inside an airway for the rendering tests: the cameras of a few
// P1 trials (along passages, at least 2 mm from the wall) and, from the same
// centres, views in directions drawn at random.

#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Core/SyntheticExperiment.h>

#include <Eigen/Geometry>

#include <random>
#include <vector>

namespace vimlop::fixtures
{

inline std::vector<CameraPose> posesInside(const RegistrationModel& model, int trials)
{
  std::vector<CameraPose> poses;
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  SyntheticOptions options;
  options.points = 50; // the cameras are what is wanted here
  for (int seed = 1; seed <= trials; ++seed)
  {
    const SyntheticTrial trial = makeSyntheticTrial(model, options, 100 + seed);
    for (const CameraPose& camera : trial.trueCamerasCT)
    {
      poses.push_back(camera);
      const Eigen::Vector3d look(gauss(rng), gauss(rng), gauss(rng));
      const Eigen::Vector3d up(gauss(rng), gauss(rng), gauss(rng));
      if (look.norm() > 1e-3 && look.normalized().cross(up.normalized()).norm() > 0.1)
      {
        poses.push_back(CameraPose::lookAt(camera.centre, camera.centre + look, up));
      }
    }
  }
  return poses;
}

} // namespace vimlop::fixtures

#endif
