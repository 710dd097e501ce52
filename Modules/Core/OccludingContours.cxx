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
  // The view frustum as half-spaces n · p + d >= 0 in camera coordinates: the
  // near plane and the four image sides (each linear in p).
  const double left = (-0.5 + options.imageMarginPx - k.cx) / k.fx;
  const double right = (k.widthPx - 0.5 - options.imageMarginPx - k.cx) / k.fx;
  const double top = (-0.5 + options.imageMarginPx - k.cy) / k.fy;
  const double bottom = (k.heightPx - 0.5 - options.imageMarginPx - k.cy) / k.fy;
  const Eigen::Vector4d planes[5] = { { 0, 0, 1, -options.nearClipMm }, { 1, 0, -left, 0 },
    { -1, 0, right, 0 }, { 0, 1, -top, 0 }, { 0, -1, bottom, 0 } };
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
    const Eigen::Vector3d n =
      (mesh.faceNormals()[edge.face0] + mesh.faceNormals()[edge.face1]).normalized();
    const Eigen::Vector3d nc = toCamera * n;
    Eigen::Vector2d pixelNormal(k.fx * nc.x(), k.fy * nc.y());
    if (!(pixelNormal.norm() > 1e-12))
    {
      continue; // normal along the optical axis: no image orientation
    }
    pixelNormal.normalize();
    // Clip the edge to the view frustum, so that samples are only spent on
    // what the image shows.
    double t0 = 0.0;
    double t1 = 1.0;
    for (const Eigen::Vector4d& plane : planes)
    {
      const double da = plane.head<3>().dot(ac) + plane[3];
      const double db = plane.head<3>().dot(bc) + plane[3];
      if (da < 0.0 && db < 0.0)
      {
        t1 = -1.0;
        break;
      }
      if (da < 0.0)
      {
        t0 = std::max(t0, da / (da - db));
      }
      else if (db < 0.0)
      {
        t1 = std::min(t1, da / (da - db));
      }
    }
    if (!(t1 > t0))
    {
      continue;
    }
    const double lengthPx = (k.project(ac + t0 * (bc - ac)) - k.project(ac + t1 * (bc - ac))).norm();
    const int n_samples = std::max(1, static_cast<int>(std::ceil(lengthPx / spacing)));
    for (int s = 0; s < n_samples; ++s)
    {
      const double t = t0 + (t1 - t0) * (s + 0.5) / n_samples;
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
