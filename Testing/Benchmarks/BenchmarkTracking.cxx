// Speed of EndoscopeTracker (issue 16) on this machine: the latency of each
// frame, from the decoded frame to its pose, over a long simulated sequence
// played forward and back with pauses and fast moves (the tracking
// protocol's, ideal world), tracked from the true pose of its first frame.
// The same frames are tracked in the same run with OpenCV on all cores and
// on one thread, and, when they are wider than the tracker halves
// (maxTrackingWidthPx), also at their full size: the machines are shared,
// so the figures to compare are the ratios (against those peers, and
// against the 33.3 ms a frame lasts at 30 Hz).
//
// Usage: VIMLOPBenchmarkTracking --mesh airway.vtp [--frames N] [--seed S] [--frame-scale K]
//          [--json out.json]
// --frame-scale K renders frames K times larger (and K times the focal
// length: the same view) than the simulator's 320 x 240.
// (needs an X display for the rendering: run it under xvfb-run -a on a server)

#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationMetrics.h>
#include <vimlop/Core/Statistics.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Evaluation/TrackingProtocol.h>
#include <vimlop/Imaging/MeshIO.h>
#include <vimlop/Imaging/PolyDataConversion.h>
#include <vimlop/Pipeline/EndoscopeTracker.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <nlohmann/json.hpp>

#include <vtkPolyData.h>

#include <opencv2/core/utility.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

using namespace vimlop;

namespace
{

/// One pass of the tracker over the sequence.
struct Pass
{
  int threads = 0;
  /// The width the frames were tracked at, px.
  int trackedWidthPx = 0;
  Summary latencyMs;
  double meanErrorMm = 0.0;
  int lost = 0;
};

Pass trackAll(const TriangleMesh& mesh, const SimulatedVideo& video, int threads,
  const EndoscopeTrackerOptions& options = {})
{
  cv::setNumThreads(threads);
  EndoscopeTracker tracker(mesh, video.intrinsics, options);
  tracker.start(video.frames.front(), video.camerasCT.front());
  std::vector<double> latency, error;
  Pass pass;
  pass.threads = threads;
  pass.trackedWidthPx = tracker.trackedCamera().widthPx;
  for (std::size_t f = 1; f < video.frames.size(); ++f)
  {
    const TrackedFrame t = tracker.track(video.frames[f]);
    latency.push_back(t.latencyMs);
    pass.lost += t.state == TrackingState::Lost;
    if (t.state != TrackingState::Lost)
    {
      error.push_back(cameraPositionError(t.cameraToCT, video.camerasCT[f]));
    }
  }
  pass.latencyMs = summarize(latency);
  pass.meanErrorMm = summarize(error).mean;
  return pass;
}

nlohmann::json toJson(const Pass& p)
{
  return { { "opencv_threads", p.threads }, { "tracked_width_px", p.trackedWidthPx },
    { "latency_ms_median", p.latencyMs.median }, { "latency_ms_p99", p.latencyMs.p99 },
    { "latency_ms_max", p.latencyMs.max }, { "lost_frames", p.lost },
    { "camera_position_mm_mean", p.meanErrorMm } };
}

} // namespace

int main(int argc, char** argv)
{
  std::string meshPath, jsonPath;
  EndoscopeSimulationOptions simulation = TrackingProtocolOptions::defaultSimulation();
  simulation.frames = 300;
  int frameScale = 1;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (!std::strcmp(argv[i], "--mesh"))
      meshPath = argv[i + 1];
    else if (!std::strcmp(argv[i], "--frames"))
      simulation.frames = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--seed"))
      simulation.seed = std::strtoull(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--json"))
      jsonPath = argv[i + 1];
    else if (!std::strcmp(argv[i], "--frame-scale"))
      frameScale = std::atoi(argv[i + 1]);
  }
  if (meshPath.empty() || simulation.frames < 2 || frameScale < 1 || frameScale > 8)
  {
    std::fprintf(stderr,
      "usage: %s --mesh airway.vtp [--frames N (at least 2)] [--seed S] [--frame-scale K (1 to "
      "8)] [--json out.json]\n",
      argv[0]);
    return 2;
  }
  simulation.intrinsics = simulation.intrinsics.resampled(frameScale);
  try
  {
    const TriangleMesh mesh = toTriangleMesh(readPolyData(meshPath));
    const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
    std::fprintf(stderr, "rendering %d frames...\n", simulation.frames);
    const SimulatedVideo video = simulateEndoscopeVideo(model, simulation, {});
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    // All cores first: the first pass also warms the caches for the second.
    trackAll(mesh, video, cores);
    const Pass all = trackAll(mesh, video, cores);
    const Pass one = trackAll(mesh, video, 1);
    std::vector<Pass> passes = { all, one };
    if (all.trackedWidthPx < video.intrinsics.widthPx)
    {
      EndoscopeTrackerOptions fullSize;
      fullSize.maxTrackingWidthPx = video.intrinsics.widthPx;
      passes.push_back(trackAll(mesh, video, cores, fullSize));
    }
    const double frameMs = 1000.0 / 30.0;
    std::printf("tracking %zu frames of %d x %d pixels (seed %llu, ideal world), mesh of %d "
                "triangles\n",
      video.frames.size() - 1, video.intrinsics.widthPx, video.intrinsics.heightPx,
      static_cast<unsigned long long>(simulation.seed), mesh.numberOfFaces());
    for (const Pass& p : passes)
    {
      std::printf("  OpenCV on %d thread(s), tracked %d px wide: latency median %.2f ms, p99 "
                  "%.2f ms, max %.2f ms; %d lost; camera error mean %.3f mm\n",
        p.threads, p.trackedWidthPx, p.latencyMs.median, p.latencyMs.p99, p.latencyMs.max, p.lost,
        p.meanErrorMm);
    }
    std::printf("  median latency / 33.3 ms (a frame at 30 Hz): %.2f on %d thread(s), %.2f on 1\n",
      all.latencyMs.median / frameMs, cores, one.latencyMs.median / frameMs);
    std::printf("  speed-up of %d thread(s) over 1, median latency: %.2f\n", cores,
      one.latencyMs.median / all.latencyMs.median);
    if (passes.size() > 2)
    {
      std::printf("  speed-up of tracking %d px wide over the full %d px: %.2f\n",
        all.trackedWidthPx, video.intrinsics.widthPx,
        passes[2].latencyMs.median / all.latencyMs.median);
    }
    if (!jsonPath.empty())
    {
      nlohmann::json report = { { "benchmark", "tracking" }, { "frames", video.frames.size() - 1 },
        { "seed", simulation.seed }, { "width_px", video.intrinsics.widthPx },
        { "height_px", video.intrinsics.heightPx }, { "all_cores", toJson(all) },
        { "one_thread", toJson(one) },
        { "median_over_frame_time_30hz", all.latencyMs.median / frameMs },
        { "speedup_all_cores_over_one", one.latencyMs.median / all.latencyMs.median } };
      if (passes.size() > 2)
      {
        report["full_size"] = toJson(passes[2]);
      }
      std::ofstream(jsonPath) << report.dump(2) << "\n";
    }
  }
  catch (const Error& e)
  {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
