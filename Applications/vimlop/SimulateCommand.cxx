#include "Commands.h"

#include "CommandLine.h"
#include "TerminalEvaluationProgress.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Imaging/ModelLoading.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>
#include <vimlop/Rendering/OffscreenRendering.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <memory>
#include <vector>

namespace vimlop
{

namespace
{

struct SimulateOptions
{
  std::string mesh;
  std::string ct;
  std::string out;
  EndoscopeSimulationOptions simulation;
  /// OpenCV's k1, k2, p1, p2; the intrinsics carry them only when one is non-zero,
  /// so that the ideal world's intrinsics.yaml stays as it was.
  double k1 = 0.0;
  double k2 = 0.0;
  double p1 = 0.0;
  double p2 = 0.0;
  std::vector<double> fieldStopOffsetPx{ 0.0, 0.0 };
  std::vector<double> principalPointErrorPx{ 0.0, 0.0 };
};

void runSimulate(SimulateOptions o)
{
  const auto start = std::chrono::steady_clock::now();
  PinholeCamera& k = o.simulation.intrinsics;
  k.fy = k.fx; // square pixels, principal point at the centre
  k.cx = 0.5 * (k.widthPx - 1);
  k.cy = 0.5 * (k.heightPx - 1);
  if (o.k1 != 0.0 || o.k2 != 0.0 || o.p1 != 0.0 || o.p2 != 0.0)
  {
    k.distortion = Eigen::Vector4d(o.k1, o.k2, o.p1, o.p2);
  }
  o.simulation.fieldStop.centreOffsetPx =
    Eigen::Vector2d(o.fieldStopOffsetPx[0], o.fieldStopOffsetPx[1]);
  o.simulation.calibrationPrincipalPointErrorPx =
    Eigen::Vector2d(o.principalPointErrorPx[0], o.principalPointErrorPx[1]);
  // Before the display check: a wrong setting is reported wherever it runs.
  o.simulation.validate();
  requireOffscreenRendering("vimlop simulate");
  const TriangleMesh mesh = airwayMeshFrom(o.mesh, o.ct);
  const RegistrationModel model = makeEmbreeRegistrationModel(mesh);
  const SimulatedVideo video =
    simulateEndoscopeVideo(model, o.simulation, terminalEvaluationProgress());
  writeSimulatedVideo(video, o.out);
  std::printf("simulated %d frames of %dx%d px along a %.1f mm path (least wall distance %.2f mm) "
              "in %.1f s; wrote '%s'\n",
    o.simulation.frames, k.widthPx, k.heightPx, video.pathLengthMm(),
    video.leastWallDistanceMm(model),
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), o.out.c_str());
}

} // namespace

void addSimulateCommand(CLI::App& app)
{
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* simulate = app.add_subcommand("simulate",
    "Simulate an endoscope sequence in the airway: frames, depth maps, intrinsics, true poses, "
    "tracker CSV");
  addModelOptions(*simulate, o->mesh, o->ct);
  simulate->add_option("--out", o->out, "output folder")->required();
  simulate->add_option("--frames", o->simulation.frames, "number of frames")
    ->capture_default_str()
    ->check(CLI::Range(2, 10000));
  simulate->add_option("--seed", o->simulation.seed, "random seed (path, texture, noise)")
    ->capture_default_str();
  PinholeCamera& k = o->simulation.intrinsics;
  simulate->add_option("--width", k.widthPx, "image width, pixels")
    ->capture_default_str()
    ->check(CLI::Range(16, 8192));
  simulate->add_option("--height", k.heightPx, "image height, pixels")
    ->capture_default_str()
    ->check(CLI::Range(16, 8192));
  simulate->add_option("--focal", k.fx, "focal length, pixels (principal point at the centre)")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  simulate->add_option("--step-mm", o->simulation.trajectory.stepMm, "advance per frame, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  simulate
    ->add_option("--clearance-mm", o->simulation.trajectory.minClearanceMm,
      "least distance of the optical centre to the wall, mm")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  simulate
    ->add_option("--upright-deg", o->simulation.trajectory.uprightRollDeg,
      "keep the image up within this many degrees of superior (negative: any roll)")
    ->capture_default_str()
    ->check(CLI::Range(-1.0, 180.0));
  simulate->add_option("--noise", o->simulation.noiseSigma, "picture noise std, grey levels")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  simulate->add_option("--blur-px", o->simulation.blurSigmaPx, "picture blur std, pixels")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);

  // The error sources of a realistic world (Documentation/Simulation.md): all off by default.
  FieldStopOptions& stop = o->simulation.fieldStop;
  simulate
    ->add_option("--field-stop", stop.radiusFraction,
      "radius of the endoscope's image circle, fraction of the half-diagonal (0: none; about 0.6 "
      "for a circle as tall as a 4:3 frame)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  simulate
    ->add_option("--field-stop-px", stop.radiusPx,
      "radius of the image circle, pixels (0: none; instead of --field-stop)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  simulate
    ->add_option("--field-stop-offset-px", o->fieldStopOffsetPx,
      "centre of the image circle relative to the image centre, pixels: u,v")
    ->delimiter(',')
    ->expected(2)
    ->capture_default_str();
  simulate
    ->add_option("--field-stop-edge-px", stop.edgeSoftnessPx,
      "width of the image circle's soft edge, pixels (0: a hard step)")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  simulate
    ->add_option("--vignetting", stop.vignettingStrength,
      "fraction of brightness lost at the circle's edge (gain 1 - s (r/R)^2; 0: none)")
    ->capture_default_str();
  simulate->add_option("--k1", o->k1, "radial distortion k1 rendered into the frames (OpenCV)")
    ->capture_default_str();
  simulate->add_option("--k2", o->k2, "radial distortion k2 (OpenCV)")->capture_default_str();
  simulate->add_option("--p1", o->p1, "tangential distortion p1 (OpenCV)")->capture_default_str();
  simulate->add_option("--p2", o->p2, "tangential distortion p2 (OpenCV)")->capture_default_str();
  simulate
    ->add_option("--focal-error", o->simulation.calibrationFocalErrorRelative,
      "relative error of the focal length written to intrinsics.yaml (the frames use the true one)")
    ->capture_default_str();
  simulate
    ->add_option("--principal-point-error-px", o->principalPointErrorPx,
      "error of the principal point written to intrinsics.yaml, pixels: u,v")
    ->delimiter(',')
    ->expected(2)
    ->capture_default_str();
  simulate
    ->add_option("--tracker-latency-s", o->simulation.trackerLatencyS,
      "tracker latency, seconds: each sample reports the tip this long before its time stamp")
    ->capture_default_str();
  simulate
    ->add_option("--tracker-offset-s", o->simulation.trackerClockOffsetS,
      "tracker clock minus video clock, seconds")
    ->capture_default_str();
  simulate->callback([o] { runSimulate(*o); });
}

} // namespace vimlop
