#ifndef vimlop_CameraPoseTable_h
#define vimlop_CameraPoseTable_h

#include <vimlop/Core/FramePose.h>

#include "VIMLOPRegistrationModule.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkTable;

/**
 * @file CameraPoseTable.h
 * @brief Per-frame camera poses as a `vtkTable`, the form VTK pipelines and
 * navigation software consume.
 *
 * One row per frame. Columns: "FrameId" (vtkIntArray) and "CameraToCT"
 * (vtkDoubleArray, 16 components: the camera-to-CT 4x4 matrix in row-major
 * order, as vtkMatrix4x4::DeepCopy(const double[16]) expects). Camera axes
 * follow OpenCV (x right, y down, z forward); translation in mm.
 */

namespace vimlop
{

/// @brief The table of `poses`, in their order.
VIMLOPREGISTRATION_EXPORT vtkSmartPointer<vtkTable> makeCameraPoseTable(
  const std::vector<FramePose>& poses);

/**
 * @brief The table of tracked frames (vimlop track's tracked-poses.vtt):
 * makeCameraPoseTable() of `poses` (for a lost frame, the prediction), then
 * "State" (vtkStringArray: "tracking", "degraded" or "lost"; filter on it
 * before showing a pose) and "LatencyMs" (from the decoded frame to its
 * pose). The three vectors hold one value per frame.
 * @throws vimlop::Error when their sizes differ.
 */
VIMLOPREGISTRATION_EXPORT vtkSmartPointer<vtkTable> makeTrackedPoseTable(
  const std::vector<FramePose>& poses, const std::vector<std::string>& states,
  const std::vector<double>& latencyMs);

/**
 * @brief The poses held by a table made by makeCameraPoseTable() (or by hand
 * with the same columns).
 * @throws vimlop::Error if a column is missing or has the wrong number of
 * components, or a matrix is not a rigid transform.
 */
VIMLOPREGISTRATION_EXPORT std::vector<FramePose> readCameraPoseTable(vtkTable* table);

} // namespace vimlop

#endif
