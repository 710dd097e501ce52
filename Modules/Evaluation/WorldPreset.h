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
 * Values and their sources: Documentation/Simulation.md.
 */
struct ErrorSource
{
  std::string name;
  /// What the value is, with its unit (the x axis of P5's plot).
  std::string knob;
  double offValue = 0.0;
  double clinicalValue = 0.0;
  std::function<void(WorldSettings&, double)> set;
  /// Whether applyWorldPreset() sets this source (default true). False for
  /// the sources added after the clinical figures of the README were
  /// measured (fast motion, jitter, curved paths): P5 still varies them
  /// alone, but the clinical world stays the one those figures describe.
  bool inClinicalPreset = true;
};

/// @brief The error sources, in the order P5 reports them.
const std::vector<ErrorSource>& errorSources();

/// @brief The source named `name`. @throws vimlop::Error naming the known ones.
const ErrorSource& errorSource(const std::string& name);

/**
 * @brief Sets every error source of `settings` for the world `name`: "ideal"
 * (all off: the world of P1-P3) or "clinical" (all at their realistic
 * values). Other fields (frames, seed, image size) are kept, and so are the
 * sources outside the preset (ErrorSource::inClinicalPreset false): off by
 * default, they are set only by their own flags or by P5.
 * @throws vimlop::Error for another name: "unknown world 'x' (expected ideal or clinical)".
 */
void applyWorldPreset(WorldSettings& settings, const std::string& name);

} // namespace vimlop

#endif
