#ifndef vimlop_WorldPreset_h
#define vimlop_WorldPreset_h

#include <vimlop/Evaluation/EndoscopeSimulation.h>
#include <vimlop/Evaluation/SimulatedWorld.h>

#include <functional>
#include <string>
#include <vector>

namespace vimlop
{

/// @brief Everything that makes a simulated world: its model errors and its video's error sources.
struct WorldSettings
{
  SimulatedWorldOptions model;
  EndoscopeSimulationOptions video;
};

/**
 * @brief One error source of the simulated world, as P5 varies it and the
 * clinical preset sets it: a name, the knob it is measured against, its
 * realistic ("clinical") value and how to set it.
 *
 * `set(settings, value)` changes only the source's own fields, so sources
 * combine; at `offValue` the source is off (the ideal world's setting).
 * One exception: "distortion-calibration" needs a lens to act on, so it
 * switches on the "lens" source's lens when there is none, and removes a
 * radial-tangential lens when off. "lens" and "fisheye" share the
 * intrinsics' coefficients; each, when off, removes only a lens of its own
 * model. Values and their sources: Documentation/Simulation.md.
 */
struct ErrorSource
{
  std::string name;
  /// What the value is, with its unit (the x axis of P5's plot).
  std::string knob;
  double offValue = 0.0;
  double clinicalValue = 0.0;
  std::function<void(WorldSettings&, double)> set;
  /// Whether the clinical preset sets it (default true). False for the
  /// sources added after the README's clinical figures were measured (the
  /// fisheye, the distortion's calibration error, fast motion, jitter,
  /// curved paths): they are budget-only (P5 varies them alone) until the
  /// clinical world is measured again with them, so that the clinical preset
  /// stays the world those figures describe. The ideal world turns them off
  /// like every other source.
  bool inClinicalPreset = true;
};

/// @brief The error sources, in the order P5 reports them.
const std::vector<ErrorSource>& errorSources();

/// @brief The source named `name`. @throws vimlop::Error naming the known ones.
const ErrorSource& errorSource(const std::string& name);

/**
 * @brief Sets every error source of `settings` for the world `name`: "ideal"
 * (all off: the world of P1-P3) or "clinical" (every source with
 * ErrorSource::inClinicalPreset at its realistic value; the others are left
 * as they are). Other fields (frames, seed, image size) are kept.
 * @throws vimlop::Error for another name: "unknown world 'x' (expected ideal or clinical)".
 */
void applyWorldPreset(WorldSettings& settings, const std::string& name);

} // namespace vimlop

#endif
