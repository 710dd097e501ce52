// Speed of the two contour-visibility backends (V4) in the same run: the
// paper's z-buffer (vtkVIMLOPDepthVisibility: offscreen render, depth
// read-back, test) against Embree's ray-occlusion tests (EmbreeVisibility),
// per frame, on the occluding-contour samples of camera poses inside the
// airway (the cameras of P1 trials and views in random directions from
// them), with how often the two agree. The machines are shared: compare the
// ratio, measured side by side on the same frames.
//
// Usage: VIMLOPBenchmarkVisibility --mesh airway.vtp [--trials N] [--supersampling S]
// (needs an X display: run it under xvfb-run -a on a server)

#include <vimlop/Core/Error.h>
#include <vimlop/Core/OccludingContours.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Core/SyntheticExperiment.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Rendering/vtkVIMLOPDepthVisibility.h>

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <Eigen/Geometry>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

using namespace vimlop;

namespace
{

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<CameraPose> posesInside(const RegistrationModel& model, int trials)
{
  std::vector<CameraPose> poses;
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  SyntheticOptions options;
  options.points = 50;
  for (int seed = 1; seed <= trials; ++seed)
  {
    for (const CameraPose& camera : makeSyntheticTrial(model, options, 100 + seed).trueCamerasCT)
    {
      poses.push_back(camera);
      const Eigen::Vector3d look(gauss(rng), gauss(rng), gauss(rng));
      const Eigen::Vector3d up(gauss(rng), gauss(rng), gauss(rng));
      if (look.norm() > 1e-3 && look.normalized().cross(up.normalized()).norm() > 0.1)
      {
        poses.push_back(CameraPose::lookAt(camera.centre, camera.centre + look, up));
      }
    }
  }
  return poses;
}

} // namespace

int main(int argc, char** argv)
{
  std::string meshPath;
  int trials = 10;
  int supersampling = 3;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (!std::strcmp(argv[i], "--mesh"))
      meshPath = argv[i + 1];
    else if (!std::strcmp(argv[i], "--trials"))
      trials = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--supersampling"))
      supersampling = std::atoi(argv[i + 1]);
  }
  if (meshPath.empty() || trials < 1)
  {
    std::fprintf(stderr, "usage: %s --mesh airway.vtp [--trials N] [--supersampling S]\n", argv[0]);
    return 2;
  }
  try
  {
    const TriangleMesh mesh = toTriangleMesh(readPolyData(meshPath));
    const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
    const std::vector<CameraPose> poses = posesInside(model, trials);
    const PinholeCamera k = PinholeCamera::simulatedEndoscope();
    vtkNew<vtkVIMLOPDepthVisibility> zbuffer;
    zbuffer->SetMesh(mesh);
    zbuffer->SetSupersampling(supersampling);

    // One untimed frame: the first render creates the OpenGL context.
    std::vector<char> warm;
    zbuffer->classify(k, poses.front(), { mesh.vertices().front() }, warm);

    std::vector<double> embreeMs, zbufferMs, ratios, samples;
    size_t total = 0;
    size_t agree = 0;
    for (const CameraPose& pose : poses)
    {
      std::vector<Eigen::Vector3d> points;
      for (const ModelContourPoint& s : extractOccludingContours(mesh, k, pose))
      {
        points.push_back(s.point);
      }
      if (points.empty())
      {
        continue;
      }
      std::vector<char> a, b;
      auto start = Clock::now();
      model.visibility().classify(k, pose, points, a);
      const double embree = millisecondsSince(start);
      start = Clock::now();
      zbuffer->classify(k, pose, points, b);
      const double depth = millisecondsSince(start);
      embreeMs.push_back(embree);
      zbufferMs.push_back(depth);
      ratios.push_back(depth / std::max(embree, 1e-6));
      samples.push_back(static_cast<double>(points.size()));
      for (size_t i = 0; i < points.size(); ++i)
      {
        agree += a[i] == b[i];
      }
      total += points.size();
    }
    std::printf("visibility of contour samples: %zu frames of %d x %d pixels, median %.0f samples "
                "per frame, mesh of %d triangles, z-buffer supersampling %d\n",
      embreeMs.size(), k.widthPx, k.heightPx, summarize(samples).median, mesh.numberOfFaces(),
      supersampling);
    std::printf("  Embree ray tests:   median %.3f ms per frame\n", summarize(embreeMs).median);
    std::printf("  z-buffer rendering: median %.3f ms per frame\n", summarize(zbufferMs).median);
    std::printf("  time ratio z-buffer / Embree: median %.1f over frames (ratio of medians %.1f)\n",
      summarize(ratios).median, summarize(zbufferMs).median / summarize(embreeMs).median);
    std::printf(
      "  agreement: %.2f %% of %zu samples\n", 100.0 * agree / std::max<size_t>(total, 1), total);
  }
  catch (const Error& e)
  {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
