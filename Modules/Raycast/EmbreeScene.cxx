#include <vimlop/Raycast/EmbreeScene.h>

#include <vimlop/Core/ClosestPointOnTriangle.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <embree3/rtcore.h>

#include <cmath>
#include <string>

namespace vimlop
{

struct EmbreeScene::Internals
{
  TriangleMesh Mesh;
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;

  ~Internals()
  {
    if (this->Scene)
    {
      rtcReleaseScene(this->Scene);
    }
    if (this->Device)
    {
      rtcReleaseDevice(this->Device);
    }
  }
};

namespace
{

void throwOnDeviceError(RTCDevice device, const char* what)
{
  const RTCError code = rtcGetDeviceError(device);
  if (code != RTC_ERROR_NONE)
  {
    throw Error(
      std::string("Embree failed to ") + what + " (error code " + std::to_string(code) + ")");
  }
}

/// State of one closest-point query, updated by the per-triangle callback.
struct ClosestPointSearch
{
  const TriangleMesh* Mesh;
  Eigen::Vector3d Query;
  SurfacePoint Best;
  double BestDistance2;
};

bool closestPointCallback(RTCPointQueryFunctionArguments* args)
{
  auto* search = static_cast<ClosestPointSearch*>(args->userPtr);
  const int face = static_cast<int>(args->primID);
  const TriangleMesh& mesh = *search->Mesh;
  Eigen::Vector3d weights;
  const Eigen::Vector3d q = closestPointOnTriangle(
    search->Query, mesh.corner(face, 0), mesh.corner(face, 1), mesh.corner(face, 2), &weights);
  const double d2 = (q - search->Query).squaredNorm();
  if (d2 >= search->BestDistance2)
  {
    return false;
  }
  search->BestDistance2 = d2;
  search->Best.point = q;
  search->Best.barycentric = weights;
  search->Best.face = face;
  // Shrink the search ball, rounded up so that float round-off never culls a
  // triangle that is closer in double precision.
  args->query->radius = std::nextafter(static_cast<float>(std::sqrt(d2)), INFINITY);
  return true;
}

} // namespace

EmbreeScene::EmbreeScene(const TriangleMesh& mesh)
  : Impl(std::make_unique<Internals>())
{
  if (mesh.numberOfFaces() == 0)
  {
    throw Error("cannot build a ray-casting scene: the mesh has no faces");
  }
  this->Impl->Mesh = mesh;
  this->Impl->Device = rtcNewDevice("verbose=0");
  if (!this->Impl->Device)
  {
    throw Error("Embree could not create a device (error code " +
      std::to_string(rtcGetDeviceError(nullptr)) + ")");
  }
  this->Impl->Scene = rtcNewScene(this->Impl->Device);
  // Robust traversal: rays through shared edges and vertices never leak.
  rtcSetSceneFlags(this->Impl->Scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(this->Impl->Scene, RTC_BUILD_QUALITY_HIGH);

  RTCGeometry geometry = rtcNewGeometry(this->Impl->Device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
    RTC_FORMAT_FLOAT3, 3 * sizeof(float), static_cast<size_t>(mesh.numberOfVertices())));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
    RTC_FORMAT_UINT3, 3 * sizeof(unsigned), static_cast<size_t>(mesh.numberOfFaces())));
  if (!vertices || !indices)
  {
    rtcReleaseGeometry(geometry);
    throwOnDeviceError(this->Impl->Device, "allocate the mesh buffers");
    throw Error("Embree failed to allocate the mesh buffers");
  }
  for (int i = 0; i < mesh.numberOfVertices(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      vertices[3 * i + k] = static_cast<float>(mesh.vertices()[i][k]);
    }
  }
  for (int f = 0; f < mesh.numberOfFaces(); ++f)
  {
    for (int k = 0; k < 3; ++k)
    {
      indices[3 * f + k] = static_cast<unsigned>(mesh.faces()[f][k]);
    }
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(this->Impl->Scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(this->Impl->Scene);
  throwOnDeviceError(this->Impl->Device, "build the scene");
}

EmbreeScene::~EmbreeScene() = default;
EmbreeScene::EmbreeScene(EmbreeScene&&) noexcept = default;
EmbreeScene& EmbreeScene::operator=(EmbreeScene&&) noexcept = default;

const TriangleMesh& EmbreeScene::mesh() const
{
  return this->Impl->Mesh;
}

SurfacePoint EmbreeScene::closestPoint(const Eigen::Vector3d& query, double maxDistanceMm) const
{
  ClosestPointSearch search{ &this->Impl->Mesh, query, SurfacePoint(),
    maxDistanceMm * maxDistanceMm };
  RTCPointQuery pointQuery;
  pointQuery.x = static_cast<float>(query.x());
  pointQuery.y = static_cast<float>(query.y());
  pointQuery.z = static_cast<float>(query.z());
  pointQuery.time = 0.0f;
  pointQuery.radius = std::isfinite(maxDistanceMm)
    ? std::nextafter(static_cast<float>(maxDistanceMm), INFINITY)
    : INFINITY;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(this->Impl->Scene, &pointQuery, &context, closestPointCallback, &search);
  if (search.Best.face >= 0)
  {
    search.Best.distanceMm = std::sqrt(search.BestDistance2);
  }
  return search.Best;
}

bool EmbreeScene::isSegmentOccluded(
  const Eigen::Vector3d& from, const Eigen::Vector3d& to, double toleranceMm) const
{
  const Eigen::Vector3d d = to - from;
  const double length = d.norm();
  if (!(length > 2.0 * toleranceMm))
  {
    return false;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = static_cast<float>(from.x());
  ray.org_y = static_cast<float>(from.y());
  ray.org_z = static_cast<float>(from.z());
  ray.dir_x = static_cast<float>(d.x() / length);
  ray.dir_y = static_cast<float>(d.y() / length);
  ray.dir_z = static_cast<float>(d.z() / length);
  ray.tnear = static_cast<float>(toleranceMm);
  ray.tfar = static_cast<float>(length - toleranceMm);
  ray.time = 0.0f;
  ray.mask = 0xffffffffu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(this->Impl->Scene, &context, &ray);
  return ray.tfar == -INFINITY;
}

void EmbreeScene::areSegmentsOccluded(const Eigen::Vector3d& from,
  const std::vector<Eigen::Vector3d>& to, const std::vector<double>& toleranceMm,
  std::vector<char>& occluded) const
{
  const size_t n = to.size();
  occluded.assign(n, 0);
  std::vector<RTCRay> rays(n);
  std::vector<char> traced(n, 0);
  for (size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d d = to[i] - from;
    const double length = d.norm();
    RTCRay& ray = rays[i];
    ray.org_x = static_cast<float>(from.x());
    ray.org_y = static_cast<float>(from.y());
    ray.org_z = static_cast<float>(from.z());
    ray.time = 0.0f;
    ray.mask = 0xffffffffu;
    ray.id = static_cast<unsigned>(i);
    ray.flags = 0;
    if (!(length > 2.0 * toleranceMm[i]))
    {
      // Too short to hold an occluder: an empty interval makes Embree skip it.
      ray.dir_x = 1.0f;
      ray.dir_y = ray.dir_z = 0.0f;
      ray.tnear = 1.0f;
      ray.tfar = 0.0f;
      continue;
    }
    traced[i] = 1;
    ray.dir_x = static_cast<float>(d.x() / length);
    ray.dir_y = static_cast<float>(d.y() / length);
    ray.dir_z = static_cast<float>(d.z() / length);
    ray.tnear = static_cast<float>(toleranceMm[i]);
    ray.tfar = static_cast<float>(length - toleranceMm[i]);
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  if (n > 0)
  {
    rtcOccluded1M(
      this->Impl->Scene, &context, rays.data(), static_cast<unsigned>(n), sizeof(RTCRay));
  }
  for (size_t i = 0; i < n; ++i)
  {
    occluded[i] = traced[i] && rays[i].tfar == -INFINITY ? 1 : 0;
  }
}

std::optional<SurfacePoint> EmbreeScene::castRay(
  const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double maxDistanceMm) const
{
  // Embree asserts (and aborts) on a ray it cannot trace; say what was wrong instead.
  if (!origin.allFinite() || !direction.allFinite() || direction.isZero(0.0) ||
    !(maxDistanceMm >= 0.0))
  {
    throw Error(formatText("ray casting: a ray from (%g, %g, %g) along (%g, %g, %g) up to %g mm "
                           "cannot be traced",
      origin.x(), origin.y(), origin.z(), direction.x(), direction.y(), direction.z(),
      maxDistanceMm));
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit hit;
  hit.ray.org_x = static_cast<float>(origin.x());
  hit.ray.org_y = static_cast<float>(origin.y());
  hit.ray.org_z = static_cast<float>(origin.z());
  hit.ray.dir_x = static_cast<float>(direction.x());
  hit.ray.dir_y = static_cast<float>(direction.y());
  hit.ray.dir_z = static_cast<float>(direction.z());
  hit.ray.tnear = 0.0f;
  hit.ray.tfar = std::isfinite(maxDistanceMm) ? static_cast<float>(maxDistanceMm) : INFINITY;
  hit.ray.time = 0.0f;
  hit.ray.mask = 0xffffffffu;
  hit.ray.id = 0;
  hit.ray.flags = 0;
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(this->Impl->Scene, &context, &hit);
  if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
  {
    return std::nullopt;
  }
  SurfacePoint p;
  p.face = static_cast<int>(hit.hit.primID);
  // Embree's (u, v) weigh corners 1 and 2.
  p.barycentric = Eigen::Vector3d(1.0 - hit.hit.u - hit.hit.v, hit.hit.u, hit.hit.v);
  const TriangleMesh& mesh = this->Impl->Mesh;
  p.point = p.barycentric[0] * mesh.corner(p.face, 0) + p.barycentric[1] * mesh.corner(p.face, 1) +
    p.barycentric[2] * mesh.corner(p.face, 2);
  p.distanceMm = (p.point - origin).norm();
  return p;
}

} // namespace vimlop
