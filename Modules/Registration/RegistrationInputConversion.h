#ifndef vimlop_RegistrationInputConversion_h
#define vimlop_RegistrationInputConversion_h

#include <vimlop/Core/RegistrationData.h>
#include <vimlop/Core/TriangleMesh.h>

#include "VIMLOPRegistrationModule.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkPolyData;
class vtkTable;

/**
 * @file RegistrationInputConversion.h
 * @brief The VTK forms of a registration's inputs, as vtkVIMLOPRegistration's
 * input ports and a result folder's files hold them, and their conversion to
 * and from Core's structs.
 *
 * Layouts (names are case-sensitive):
 * - **Model surface** (vtkPolyData): polygons (triangles, or polygons that
 *   are fanned into triangles) in the CT frame, mm. Faces are oriented so
 *   that their normals point into the air: a cell array "Normals" (3
 *   components), when present, decides each face's orientation; without it
 *   the orientation is computed (see toModelMesh()).
 * - **SfM points** (vtkPolyData): points in the SfM frame (SfM units);
 *   optional point array "Covariance" (9 components: the row-major 3 x 3
 *   covariance in mm² along the SfM axes, see NoiseModel.h).
 * - **Frame table** (vtkTable): one row per video frame. Columns "FrameId"
 *   (integer), "Fx", "Fy", "Cx", "Cy" (pixels, OpenCV convention),
 *   "WidthPx", "HeightPx" (integers) and "CameraToSfm" (16 components: the
 *   row-major camera-to-SfM 4 x 4 matrix, OpenCV camera axes, as
 *   vtkMatrix4x4::DeepCopy(const double*) reads it).
 * - **Video contours** (vtkPolyData): one point per contour point at
 *   (u, v, 0) in pixels (OpenCV convention: centre of the top-left pixel at
 *   (0, 0), v down); point arrays "FrameId" (integer, a FrameId of the frame
 *   table) and "ContourNormal" (2 components: the unit contour normal in
 *   pixel axes, from the nearer, occluding side to the farther side).
 */

namespace vimlop
{

/**
 * @brief The model surface as a TriangleMesh with normals into the air.
 *
 * With a cell array "Normals", a face whose vertex order disagrees with its
 * normal is reversed. Without one, the faces are first given one consistent
 * orientation (vtkPolyDataNormals) and then, for a closed surface, turned so
 * that the normals point into the air the surface encloses; `note` (when
 * given) then says so, for a warning. An open surface without normals keeps
 * the orientation of its first polygon, and the note says that too.
 * @throws vimlop::Error "model surface: ..." without polygons, with a
 * "Normals" array of the wrong shape, or with non-finite points.
 */
VIMLOPREGISTRATION_EXPORT TriangleMesh toModelMesh(vtkPolyData* surface, std::string* note);

/**
 * @brief The registration data held by the SfM points, the frame table and the
 * video contours (each may be null except the points).
 *
 * Points without a "Covariance" array get `defaultSigmaMm`² I (isotropic).
 * Frames keep the table's row order; each gets the contour points whose
 * FrameId is its own, in their order.
 * @throws vimlop::Error naming the input and the problem: no points, a
 * missing or malformed column or array, a frame id twice in the table,
 * contours without a frame table, or contour points whose frame id is not in
 * the frame table (the table and the contours disagree).
 */
VIMLOPREGISTRATION_EXPORT RegistrationData toRegistrationData(
  vtkPolyData* sfmPoints, vtkTable* frames, vtkPolyData* contours, double defaultSigmaMm);

/// @brief The SfM points of `data` with their "Covariance" array (and a vertex per point).
VIMLOPREGISTRATION_EXPORT vtkSmartPointer<vtkPolyData> makeSfmPointPolyData(
  const RegistrationData& data);

/// @brief The frame table of `frames`, in their order.
VIMLOPREGISTRATION_EXPORT vtkSmartPointer<vtkTable> makeFrameTable(
  const std::vector<VideoFrame>& frames);

/// @brief The video contours of `frames` (and a vertex per point).
VIMLOPREGISTRATION_EXPORT vtkSmartPointer<vtkPolyData> makeContourPolyData(
  const std::vector<VideoFrame>& frames);

} // namespace vimlop

#endif
