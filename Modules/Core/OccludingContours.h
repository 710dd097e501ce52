#ifndef vimlop_OccludingContours_h
#define vimlop_OccludingContours_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/ModelContourPoint.h>
#include <vimlop/Core/PinholeCamera.h>
#include <vimlop/Core/TriangleMesh.h>

#include <vector>

namespace vimlop
{

/// @brief Where on the mesh the occluding contour is traced (V3).
enum class ContourGenerator
{
  /// Mesh edges between a front-facing and a back-facing face (the paper's).
  MeshEdges,
  /// Zero crossings, inside faces, of n(p) · (c - p) with n linearly
  /// interpolated from angle-weighted vertex normals: the contour of the
  /// smooth surface the mesh approximates, which moves continuously with the
  /// camera instead of jumping from edge to edge.
  InterpolatedNormals
};

/// @brief Options of occluding-contour extraction (V3).
struct OccludingContourOptions
{
  ContourGenerator generator = ContourGenerator::MeshEdges;
  /// Distance between samples along a contour edge in the image, pixels (default 1).
  double sampleSpacingPx = 1.0;
  /// Samples nearer the camera than this along its axis are dropped, mm (default 0.1).
  double nearClipMm = 0.1;
  /// Samples closer than this to the image border are dropped, pixels (default 0).
  double imageMarginPx = 0.0;
};

/**
 * @brief The occluding contours of `mesh` seen by a camera, before visibility.
 *
 * An edge is an occluding contour when one of its faces faces the camera
 * centre and the other faces away (the sign of n_f · (c - centroid_f)
 * differs). Such edges are sampled about every `sampleSpacingPx` pixels (at
 * least once), and samples in front of the camera and inside the image are
 * kept, in edge order. Hidden samples are still included: visibility is a
 * separate stage (V4, see ContourVisibility).
 */
std::vector<ModelContourPoint> extractOccludingContours(const TriangleMesh& mesh,
  const PinholeCamera& intrinsics, const CameraPose& cameraToCT,
  const OccludingContourOptions& options = OccludingContourOptions());

} // namespace vimlop

#endif
