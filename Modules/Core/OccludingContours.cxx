#include <vimlop/Core/OccludingContours.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace vimlop
{

namespace
{

/// Samples the segment [a, b] (CT) seen by a camera, with normals
/// interpolated from na to nb, about every `spacing` pixels inside the view.
class SegmentSampler
{
public:
  SegmentSampler(
    const PinholeCamera& k, const CameraPose& cameraToCT, const OccludingContourOptions& o)
    : K(k)
    , Centre(cameraToCT.centre)
    , ToCamera(cameraToCT.rotation.transpose())
    , Options(o)
    , Spacing(std::max(o.sampleSpacingPx, 1e-3))
  {
    // The view frustum as half-spaces n · p + d >= 0 in camera coordinates:
    // the near plane and the four image sides (each linear in p).
    const double left = (-0.5 + o.imageMarginPx - k.cx) / k.fx;
    const double right = (k.widthPx - 0.5 - o.imageMarginPx - k.cx) / k.fx;
    const double top = (-0.5 + o.imageMarginPx - k.cy) / k.fy;
    const double bottom = (k.heightPx - 0.5 - o.imageMarginPx - k.cy) / k.fy;
    this->Planes[0] = { 0, 0, 1, -o.nearClipMm };
    this->Planes[1] = { 1, 0, -left, 0 };
    this->Planes[2] = { -1, 0, right, 0 };
    this->Planes[3] = { 0, 1, -top, 0 };
    this->Planes[4] = { 0, -1, bottom, 0 };
  }

  void sample(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& na,
    const Eigen::Vector3d& nb, int edge, std::vector<ModelContourPoint>& out) const
  {
    const Eigen::Vector3d ac = this->ToCamera * (a - this->Centre);
    const Eigen::Vector3d bc = this->ToCamera * (b - this->Centre);
    // Clip to the view frustum so samples are only spent on what the image shows.
    double t0 = 0.0;
    double t1 = 1.0;
    for (const Eigen::Vector4d& plane : this->Planes)
    {
      const double da = plane.head<3>().dot(ac) + plane[3];
      const double db = plane.head<3>().dot(bc) + plane[3];
      if (da < 0.0 && db < 0.0)
      {
        return;
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
      return;
    }
    const PinholeCamera& k = this->K;
    const double lengthPx =
      (k.project(ac + t0 * (bc - ac)) - k.project(ac + t1 * (bc - ac))).norm();
    const int count = std::max(1, static_cast<int>(std::ceil(lengthPx / this->Spacing)));
    for (int s = 0; s < count; ++s)
    {
      const double t = t0 + (t1 - t0) * (s + 0.5) / count;
      const Eigen::Vector3d pc = ac + t * (bc - ac);
      if (pc.z() < this->Options.nearClipMm)
      {
        continue;
      }
      const Eigen::Vector2d pixel = k.project(pc);
      if (!k.isInImage(pixel, this->Options.imageMarginPx))
      {
        continue;
      }
      const Eigen::Vector3d n = ((1.0 - t) * na + t * nb).normalized();
      const Eigen::Vector3d nc = this->ToCamera * n;
      Eigen::Vector2d pixelNormal(k.fx * nc.x(), k.fy * nc.y());
      if (!(pixelNormal.norm() > 1e-12) || !n.allFinite())
      {
        continue; // normal along the optical axis: no image orientation
      }
      ModelContourPoint sample;
      sample.point = a + t * (b - a);
      sample.normal = n;
      sample.pixel = pixel;
      sample.pixelNormal = pixelNormal.normalized();
      sample.edge = edge;
      out.push_back(sample);
    }
  }

private:
  const PinholeCamera& K;
  Eigen::Vector3d Centre;
  Eigen::Matrix3d ToCamera;
  const OccludingContourOptions& Options;
  double Spacing;
  Eigen::Vector4d Planes[5];
};

void meshEdgeContours(const TriangleMesh& mesh, const Eigen::Vector3d& c,
  const SegmentSampler& sampler, std::vector<ModelContourPoint>& samples)
{
  const int nf = mesh.numberOfFaces();
  // +1 facing the camera, -1 facing away, 0 for zero-area faces (never contours).
  std::vector<signed char> facing(static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f)
  {
    const double s = mesh.faceNormals()[f].dot(c - mesh.corner(f, 0));
    facing[f] = mesh.faceAreas()[f] > 0.0 ? (s > 0.0 ? 1 : -1) : 0;
  }
  const std::vector<MeshEdge>& edges = mesh.edges();
  for (int e = 0; e < static_cast<int>(edges.size()); ++e)
  {
    const MeshEdge& edge = edges[e];
    if (edge.isBoundary() || facing[edge.face0] * facing[edge.face1] >= 0)
    {
      continue;
    }
    const Eigen::Vector3d n =
      (mesh.faceNormals()[edge.face0] + mesh.faceNormals()[edge.face1]).normalized();
    sampler.sample(mesh.vertices()[edge.vertex0], mesh.vertices()[edge.vertex1], n, n, e, samples);
  }
}

void interpolatedNormalContours(const TriangleMesh& mesh, const Eigen::Vector3d& c,
  const SegmentSampler& sampler, std::vector<ModelContourPoint>& samples)
{
  const std::vector<Eigen::Vector3d>& v = mesh.vertices();
  const std::vector<Eigen::Vector3d>& n = mesh.vertexNormals();
  std::vector<double> g(v.size());
  for (size_t i = 0; i < v.size(); ++i)
  {
    g[i] = n[i].dot(c - v[i]);
  }
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    const Eigen::Vector3i& tri = mesh.faces()[f];
    Eigen::Vector3d crossing[2];
    Eigen::Vector3d normal[2];
    int found = 0;
    for (int k = 0; k < 3 && found < 2; ++k)
    {
      const int i = tri[k];
      const int j = tri[(k + 1) % 3];
      // A sign change on the edge (ties count as non-negative): one crossing.
      if ((g[i] < 0.0) != (g[j] < 0.0))
      {
        const double t = g[i] / (g[i] - g[j]);
        crossing[found] = v[i] + t * (v[j] - v[i]);
        normal[found] = (1.0 - t) * n[i] + t * n[j];
        ++found;
      }
    }
    if (found == 2)
    {
      sampler.sample(
        crossing[0], crossing[1], normal[0], normal[1], mesh.faceEdges()[f][0], samples);
    }
  }
}

} // namespace

std::vector<ModelContourPoint> extractOccludingContours(const TriangleMesh& mesh,
  const PinholeCamera& k, const CameraPose& cameraToCT, const OccludingContourOptions& options)
{
  const SegmentSampler sampler(k, cameraToCT, options);
  std::vector<ModelContourPoint> samples;
  // The registration extracts the contours of every frame at every
  // iteration, thousands of samples each time, and growing the vector one
  // doubling at a time cost about 4 % of the main job (perf): reserve what
  // this thread's last extraction found, plus a margin.
  thread_local size_t lastCount = 0;
  samples.reserve(lastCount + lastCount / 4);
  if (options.generator == ContourGenerator::MeshEdges)
  {
    meshEdgeContours(mesh, cameraToCT.centre, sampler, samples);
  }
  else
  {
    interpolatedNormalContours(mesh, cameraToCT.centre, sampler, samples);
  }
  lastCount = samples.size();
  return samples;
}

} // namespace vimlop
