#include "Commands.h"

#include "CommandLine.h"
#include <vimlop/Core/CanonicalPoses.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>
#include <vimlop/Imaging/FramePoseIO.h>
#include <vimlop/Imaging/ModelLoading.h>
#include <vimlop/Raycast/EmbreeRegistrationModel.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>

namespace vimlop
{

namespace
{

struct CanonicalCommandOptions
{
  std::string mesh;
  std::string ct;
  std::string out;
  bool json = false;
  CanonicalPoseOptions poses;
};

void runCanonical(CanonicalCommandOptions o)
{
  if (o.mesh.empty() && o.ct.empty())
  {
    throw Error("give --mesh or --ct");
  }
  const RegistrationModel model = makeEmbreeRegistrationModel(airwayMeshFrom(o.mesh, o.ct));
  const std::vector<CameraPose> poses = makeCanonicalPoses(model, o.poses);
  std::vector<FramePose> numbered;
  for (size_t i = 0; i < poses.size(); ++i)
  {
    numbered.push_back({ static_cast<int>(i), poses[i] });
  }
  writeFramePoses(numbered, o.out);
  CommandSummary summary;
  summary.lines.push_back(
    formatText("%zu canonical poses (%.1f mm apart, %d views per position, %zu rolls); wrote '%s'",
      poses.size(), o.poses.spacingMm, o.poses.viewsPerPosition, o.poses.rollsDeg.size(),
      o.out.c_str()));
  summary.json = { { "poses", poses.size() }, { "spacing_mm", o.poses.spacingMm },
    { "views_per_position", o.poses.viewsPerPosition }, { "rolls_deg", o.poses.rollsDeg },
    { "out", o.out } };
  printSummary(summary, o.json);
}

} // namespace

void addCanonicalCommand(CLI::App& app)
{
  auto o = std::make_shared<CanonicalCommandOptions>();
  CLI::App* c = app.add_subcommand("canonical",
    "Canonical camera poses along the airway of a template (store them with it; `vimlop warp "
    "--template-poses` carries them to a patient; `vimlop register --init canonical:FILE` starts "
    "from them)");
  addModelOptions(*c, o->mesh, o->ct);
  c->add_option("--out", o->out, "pose file (FramePose JSON)")->required();
  c->add_option("--spacing-mm", o->poses.spacingMm, "least distance between positions, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c->add_option("--clearance-mm", o->poses.minClearanceMm, "least distance to the wall, mm")
    ->capture_default_str()
    ->check(CLI::NonNegativeNumber);
  c->add_option("--look-ahead-mm", o->poses.lookAheadMm, "free length needed ahead, mm")
    ->capture_default_str()
    ->check(CLI::PositiveNumber);
  c->add_option("--views", o->poses.viewsPerPosition, "view directions per position")
    ->capture_default_str()
    ->check(CLI::Range(1, 20));
  c->add_option("--rolls-deg", o->poses.rollsDeg, "rolls about the view axis, degrees (repeatable)")
    ->delimiter(',')
    ->capture_default_str();
  addJsonFlag(*c, o->json);
  c->callback([o] { runCanonical(*o); });
}

} // namespace vimlop
