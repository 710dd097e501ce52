#ifndef vimlop_AirwaySurface_h
#define vimlop_AirwaySurface_h

#include <vimlop/Core/TriangleMesh.h>
#include <vimlop/Imaging/CTVolume.h>
#include <vimlop/Imaging/ProgressCallback.h>

#include "VIMLOPImagingModule.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkPolyData;

namespace vimlop
{

/// @brief Parameters of AirwaySurface::compute().
struct AirwaySurfaceOptions
{
  /// Triangles after decimation. Default 30000, which keeps a nasal airway's
  /// turbinates and meatuses (about 1.5 mm triangles) while closest-point
  /// and contour queries stay fast; 0 keeps the full iso-surface.
  int targetTriangles = 30000;
  /// Windowed-sinc smoothing iterations. Default 20; 0 turns smoothing off.
  int smoothingIterations = 20;
  /// Pass band of the windowed-sinc filter, in (0, 2]; lower is smoother. Default 0.1.
  double smoothingPassBand = 0.1;
};

/**
 * @brief The surface of an airway label volume, as the registration uses it,
 * and a report on its quality.
 *
 * Made by AirwaySurface::compute() in these steps:
 * 1. iso-surface at 0.5 of the label (flying edges) on the label's bounding
 *    box padded with one voxel of background, so the surface is closed even
 *    where the airway meets the edge of the CT;
 * 2. topology-preserving decimation (vtkDecimatePro, no splitting) to
 *    `targetTriangles`, on the voxel staircase, where it removes flat runs
 *    first and folds or pinches fewer triangles than on a smoothed surface;
 * 3. windowed-sinc smoothing, which removes the staircase without the
 *    shrinking of Laplacian smoothing (the cavity keeps its volume);
 * 4. the largest connected piece is kept (specks from single voxels go);
 * 5. points are mapped to the CT frame with the label's direction matrix
 *    (VTK 9.1 filters ignore vtkImageData's direction, so the work is done in
 *    index-times-spacing coordinates and mapped here);
 * 6. faces are ordered so that their normals point into the air, by
 *    orientIntoAir(): for the closed surface of steps 1-4 the rule every mesh
 *    loader applies (orientNormalsIntoAir: a closed surface whose normals
 *    point into the region it encloses has a negative signed volume, so the
 *    faces are reversed when it comes out positive), so the surface written
 *    here loads unchanged. This also undoes the winding flip of a reflecting
 *    direction matrix (det < 0, as for InVesalius projects).
 *
 * The output holds triangles, cell normals and point normals (both named
 * "Normals", unit, into the air), in the CT frame (LPS mm).
 */
struct AirwaySurface
{
  /// Triangles in the CT frame with normals into the air (see above).
  vtkSmartPointer<vtkPolyData> surface;
  int triangles = 0;
  int vertices = 0;
  /// Edges with one face: 0 for a closed surface.
  int boundaryEdges = 0;
  /// Edges with more than two faces.
  int nonManifoldEdges = 0;
  /// Pieces dropped in step 4, and their share of the iso-surface's triangles.
  int droppedPieces = 0;
  double droppedTriangleFraction = 0.0;
  /// Triangles of the iso-surface before decimation, and the target asked
  /// for (AirwaySurfaceOptions::targetTriangles): decimation only removes
  /// triangles, so a target above the iso-surface's count keeps them all.
  int isoSurfaceTriangles = 0;
  int targetTriangles = 0;
  /// Volume enclosed by the surface (mm^3), from the divergence theorem.
  double enclosedVolumeMm3 = 0.0;
  /// Surface area (mm^2).
  double areaMm2 = 0.0;

  /**
   * @brief Extracts the surface of the voxels where `label` is non-zero.
   * @throws vimlop::Error if the label is empty, not 3-D, inconsistent, or
   * the options are out of range.
   */
  VIMLOPIMAGING_EXPORT static AirwaySurface compute(const CTVolume& label,
    const AirwaySurfaceOptions& options, const ProgressCallback& progress = ProgressCallback());

  /// @brief "surface N triangles, M vertices, encloses V cm^3, area A cm^2, E open edges, F
  /// non-manifold edges", as `vimlop segment` prints it.
  VIMLOPIMAGING_EXPORT std::string summaryText() const;
  /// @brief What a user should know of the surface: open or non-manifold edges,
  /// disconnected pieces over 1 % of it that were dropped, and a triangle
  /// target above what the iso-surface has (empty when none).
  VIMLOPIMAGING_EXPORT std::vector<std::string> warnings() const;

  /**
   * @brief `mesh` (CT frame) with its normals into the air of `label` (the
   * voxels where it is non-zero).
   *
   * A closed surface follows the loaders' rule, orientNormalsIntoAir(), so
   * producer and loaders cannot disagree. An open surface encloses nothing
   * and that rule keeps its faces as they are, so they must point into the
   * air already; the label knows the air side: the faces are reversed when
   * more of their normals lead out of the label's voxels than into them
   * (probed half a voxel either side of each face). compute()'s surface is
   * closed by construction (step 1), so for it this only guards the later steps.
   * @throws vimlop::Error for a mesh without faces.
   */
  VIMLOPIMAGING_EXPORT static TriangleMesh orientIntoAir(
    const TriangleMesh& mesh, const CTVolume& label);
};

} // namespace vimlop

#endif
