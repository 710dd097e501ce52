#ifndef vimlop_TubeCameras_h
#define vimlop_TubeCameras_h

// Cameras along the folded tube of TestMeshes.h, for the tests of the
// checks of tracked poses against the CT.

#include <vimlop/Core/CameraPose.h>

#include <cmath>
#include <vector>

namespace vimlop::fixtures
{

/// Cameras `first` to `first + n - 1` along the folded tube (radius 4 mm),
/// looking down it and turned a little, as a scope moving through it sees it.
inline std::vector<CameraPose> camerasAlongTheTube(int n, int first = 0)
{
  std::vector<CameraPose> cameras;
  for (int i = first; i < first + n; ++i)
  {
    const double z = 8.0 + 1.5 * i;
    cameras.push_back(CameraPose::lookAt(Eigen::Vector3d(0.3 * std::sin(i), 0.2, z),
      Eigen::Vector3d(0.5, -0.3 * i, z + 20.0), Eigen::Vector3d::UnitY()));
  }
  return cameras;
}

} // namespace vimlop::fixtures

#endif
