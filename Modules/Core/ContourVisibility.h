#ifndef vimlop_ContourVisibility_h
#define vimlop_ContourVisibility_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/PinholeCamera.h>

#include <Eigen/Core>

#include <vector>

namespace vimlop
{

/**
 * @brief Decides which surface points a camera sees (V4).
 *
 * The registration asks it, every iteration and for every frame, which model
 * contour samples are visible from the frame's current camera. Backends: a
 * ray-occlusion test (EmbreeVisibility, Raycast module) and the paper's
 * z-buffer of an offscreen rendering (Rendering module). A point counts as
 * visible when nothing of the model lies between the camera centre and it.
 */
class ContourVisibility
{
public:
  virtual ~ContourVisibility() = default;

  /**
   * @brief Sets `visible[i]` to 1 when `pointsCT[i]` (mm, CT frame, on the
   * model surface) is seen by the camera, else 0.
   */
  virtual void classify(const PinholeCamera& intrinsics, const CameraPose& cameraToCT,
    const std::vector<Eigen::Vector3d>& pointsCT, std::vector<char>& visible) const = 0;

  /// @brief True when classify() may run for several frames at once.
  virtual bool isThreadSafe() const = 0;
};

} // namespace vimlop

#endif
