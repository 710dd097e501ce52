#include "OccludingContours.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace vimlop
{

std::vector<ModelContourPoint> extractOccludingContours(const TriangleMesh& mesh,
  const PinholeCamera& k, const CameraPose& cameraToCT, const OccludingContourOptions& options)
{
  const Eigen::Vector3d& c = cameraToCT.centre;
  const int nf = mesh.numberOfFaces();
  // +1 facing the camera, -1 facing away, 0 for zero-area faces (never contours).
  std::vector<signed char> facing(static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f)
  {
    const double s = mesh.faceNormals()[f].dot(c - mesh.corner(f, 0));
    facing[f] = mesh.faceAreas()[f] > 0.0 ? (s > 0.0 ? 1 : -1) : 0;
  }
  const Eigen::Matrix3d toCamera = cameraToCT.rotation.transpose();
  const double spacing = std::max(options.sampleSpacingPx, 1e-3);
  std::vector<ModelContourPoint> samples;
  const std::vector<MeshEdge>& edges = mesh.edges();
  for (int e = 0; e < static_cast<int>(edges.size()); ++e)
  {
    const MeshEdge& edge = edges[e];
    if (edge.isBoundary() || facing[edge.face0] * facing[edge.face1] >= 0)
    {
      continue;
    }
    const Eigen::Vector3d& a = mesh.vertices()[edge.vertex0];
    const Eigen::Vector3d& b = mesh.vertices()[edge.vertex1];
    const Eigen::Vector3d ac = toCamera * (a - c);
    const Eigen::Vector3d bc = toCamera * (b - c);
    if (ac.z() < options.nearClipMm && bc.z() < options.nearClipMm)
    {
      continue;
    }
    const Eigen::Vector3d n =
      (mesh.faceNormals()[edge.face0] + mesh.faceNormals()[edge.face1]).normalized();
    const Eigen::Vector3d nc = toCamera * n;
    Eigen::Vector2d pixelNormal(k.fx * nc.x(), k.fy * nc.y());
    if (!(pixelNormal.norm() > 1e-12))
    {
      continue; // normal along the optical axis: no image orientation
    }
    pixelNormal.normalize();
    // Number of samples from the projected length (clipped ends use the near plane).
    const Eigen::Vector3d ap = ac.z() >= options.nearClipMm
      ? ac
      : ac + (bc - ac) * ((options.nearClipMm - ac.z()) / (bc.z() - ac.z()));
    const Eigen::Vector3d bp = bc.z() >= options.nearClipMm
      ? bc
      : bc + (ac - bc) * ((options.nearClipMm - bc.z()) / (ac.z() - bc.z()));
    const double lengthPx = (k.project(ap) - k.project(bp)).norm();
    const int n_samples = std::max(1, static_cast<int>(std::ceil(lengthPx / spacing)));
    for (int s = 0; s < n_samples; ++s)
    {
      const double t = (s + 0.5) / n_samples;
      const Eigen::Vector3d pc = ac + t * (bc - ac);
      if (pc.z() < options.nearClipMm)
      {
        continue;
      }
      const Eigen::Vector2d pixel = k.project(pc);
      if (!k.isInImage(pixel, options.imageMarginPx))
      {
        continue;
      }
      ModelContourPoint sample;
      sample.point = a + t * (b - a);
      sample.normal = n;
      sample.pixel = pixel;
      sample.pixelNormal = pixelNormal;
      sample.edge = e;
      samples.push_back(sample);
    }
  }
  return samples;
}

} // namespace vimlop
