#ifndef vimlop_TemplateWarp_h
#define vimlop_TemplateWarp_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/FramePose.h>
#include <vimlop/Imaging/DisplacementField.h>

#include "VIMLOPImagingModule.h"

#include <vtkSmartPointer.h>

#include <Eigen/Core>

#include <vector>

class vtkPolyData;

/**
 * @file TemplateWarp.h
 * @brief Carrying template meshes and camera poses into a patient's CT frame
 * through a template-to-patient map x -> x + u(x) (DESIGN section 2, V13).
 */

namespace vimlop
{

/**
 * @brief The Jacobian J = I + du/dx (3x3) of the map x -> x + u(x) at
 * `pointMm`, by central differences over one grid step (the smallest grid
 * spacing) along each frame axis; one-sided where a central step would leave
 * the grid. Exact for fields that are affine in x.
 */
VIMLOPIMAGING_EXPORT Eigen::Matrix3d mapJacobian(
  const DisplacementField& field, const Eigen::Vector3d& pointMm);

/**
 * @brief A camera pose carried by the map: the optical centre goes through
 * the map, the orientation is turned by the rotation part, by polar
 * decomposition, of the map's local Jacobian at the centre: R' = rot(J) R.
 * A rigid map therefore moves cameras rigidly, exactly.
 */
VIMLOPIMAGING_EXPORT CameraPose warpCameraPose(
  const CameraPose& pose, const DisplacementField& field);

/// @brief warpCameraPose() on every pose; frame ids are kept.
VIMLOPIMAGING_EXPORT std::vector<FramePose> warpFramePoses(
  const std::vector<FramePose>& poses, const DisplacementField& field);

/**
 * @brief A copy of `surface` with every point carried by the map and the
 * normals ("Normals", cell and point) recomputed from the new geometry. The
 * triangles keep their order: a map without folds (positive Jacobian
 * determinant, as a diffeomorphic registration gives) keeps normals pointing
 * into the air.
 */
VIMLOPIMAGING_EXPORT vtkSmartPointer<vtkPolyData> warpSurface(
  vtkPolyData* surface, const DisplacementField& field);

} // namespace vimlop

#endif
