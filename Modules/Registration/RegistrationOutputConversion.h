#ifndef vimlop_RegistrationOutputConversion_h
#define vimlop_RegistrationOutputConversion_h

#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/RegistrationResult.h>

#include "VIMLOPRegistrationModule.h"

#include <vtkSmartPointer.h>

class vtkPolyData;
class vtkTable;

/**
 * @file RegistrationOutputConversion.h
 * @brief The VTK forms of a registration's results, as vtkVIMLOPRegistration's
 * output ports and a result folder's files hold them, and back.
 *
 * Layouts (names are case-sensitive):
 * - **Registered points** (vtkPolyData): the SfM points mapped by T into the
 *   CT frame (mm), a vertex each; point arrays "SfmPosition" (3 components,
 *   the input position, SfM frame), "Inlier" (unsigned char, 1 for a 3-D
 *   inlier at the final estimate) and "MatchedModelPoint" (3 components, the
 *   model point each matched, CT frame, mm).
 * - **Camera poses** (vtkTable): one row per frame, the columns of
 *   CameraPoseTable.h ("FrameId", "CameraToCT": row-major camera-to-CT 4 x 4,
 *   OpenCV camera axes, mm) and "ContourPoints", "MatchedContourPoints",
 *   "InlierContourPoints", "VisibleModelSamples" (integers),
 *   "ContourErrorPx" (mean distance of matched pairs) and
 *   "ContourErrorInliersPx" (over inliers), pixels.
 * - **Contour correspondences** (vtkPolyData): one line cell per matched
 *   video contour point, from the video point (u, v, 0) to its model contour
 *   sample's projection (u, v, 0), pixels (OpenCV convention); cell arrays
 *   "FrameId" (integer), "VideoIndex" (the point's index in its frame's
 *   contour), "Inlier" (unsigned char) and "ModelPoint" (3 components: the
 *   model sample, CT frame, mm).
 */

namespace vimlop
{

/// @brief The registered points of `result` for the SfM points of `data`.
VIMLOPREGISTRATION_EXPORT vtkSmartPointer<vtkPolyData> makeRegisteredPointPolyData(
  const RegistrationData& data, const RegistrationResult& result);

/// @brief The per-frame camera poses in CT with their contour metrics.
VIMLOPREGISTRATION_EXPORT vtkSmartPointer<vtkTable> makeFrameResultTable(
  const RegistrationResult& result);

/// @brief The matched contour pairs of every frame.
VIMLOPREGISTRATION_EXPORT vtkSmartPointer<vtkPolyData> makeCorrespondencePolyData(
  const RegistrationResult& result);

/**
 * @brief Reads the inlier flags and matched model points of registered points
 * back into `result` (pointInliers, pointMatches).
 * @throws vimlop::Error if an array is missing or the point count differs from `expectedPoints`.
 */
VIMLOPREGISTRATION_EXPORT void readRegisteredPoints(
  vtkPolyData* points, int expectedPoints, RegistrationResult& result);

/**
 * @brief Reads contour correspondences back into the frames of `result`
 * (matched to frames by FrameId; each frame's correspondences are replaced).
 * @throws vimlop::Error if an array is missing or a frame id is unknown.
 */
VIMLOPREGISTRATION_EXPORT void readCorrespondences(
  vtkPolyData* correspondences, RegistrationResult& result);

} // namespace vimlop

#endif
