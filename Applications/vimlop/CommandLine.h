#ifndef vimlop_CommandLine_h
#define vimlop_CommandLine_h

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

/**
 * @file CommandLine.h
 * @brief Small helpers the subcommands share: list parsing, the flags of
 * the main job and of pose serving, and safe output.
 */

namespace CLI
{
class App;
class ParseError;
} // namespace CLI

namespace vimlop
{

struct CTReadOptions;
struct ContourWindowRefinementOptions;
struct ContourRelocalisationOptions;
struct EndoscopeSimulationOptions;
struct EndoscopeTrackerOptions;
struct TrackerLagOptions;
struct PinholeCamera;
struct PoseServingOptions;
struct PoseStreamServerOptions;
struct RegistrationRecord;
struct ServedPoses;
struct SimulatedWorld;
struct SimulatedWorldOptions;
struct TemplateRegistrationOptions;
struct WorldSettings;
struct VideoRegistrationOptions;

/// @brief "a,b" as two numbers with 0 <= a <= b; `what` names the option in errors.
std::pair<double, double> parseRange(const std::string& text, const std::string& what);

/// @brief "1,2.5,3" as numbers; `what` names the option in errors.
std::vector<double> parseNumbers(const std::string& text, const std::string& what);
/// @brief "a,b,c" as a list of non-empty items.
std::vector<std::string> parseList(const std::string& text, const std::string& what);
/// @brief Numbers or items joined by commas, as the parsers above read them (shown defaults).
std::string joinNumbers(const std::vector<double>& numbers);
std::string joinList(const std::vector<std::string>& items);

/// @brief Adds --mesh and --ct, each excluding the other: the airway a command reads with
/// airwayMeshFrom (Imaging/ModelLoading.h).
void addModelOptions(CLI::App& command, std::string& mesh, std::string& ct);

/// @brief Adds --series and --resample-irregular-series (how a DICOM folder is read).
void addCTReadOptions(CLI::App& command, CTReadOptions& options);

/**
 * @brief Adds a flag for every setting of the main job to `command`, stored
 * into `options`, which must outlive the parse: one per row of
 * RegistrationOptionTable.h and VideoRegistrationOptionTable.h (with the
 * row's range as the check), Σ2d and the scale factors. The defaults shown
 * are those `options` holds: the pipeline's.
 */
void addPipelineOptions(CLI::App& command, VideoRegistrationOptions& options);

/**
 * @brief Adds a flag for every error source of the simulated world
 * (Documentation/Simulation.md) to `command`, stored into `options` (which
 * must outlive the parse): the image circle and vignetting, lens distortion,
 * calibration error and the tracker's latency and clock offset. All are off
 * by default: the ideal world. Shared by `vimlop simulate` and the protocols
 * that simulate (`vimlop evaluate video`).
 */
void addSimulationOptions(CLI::App& command, EndoscopeSimulationOptions& options);

/**
 * @brief Adds a flag for every setting of the template registration
 * (TemplateRegistrationOptions: margin, affine and SyN levels, iterations,
 * metric, smoothing) to `command`, stored into `options` (which must
 * outlive the parse); the region is the command's to set. Shared by
 * `vimlop warp` and `vimlop evaluate warp`.
 */
void addTemplateRegistrationOptions(CLI::App& command, TemplateRegistrationOptions& options);

/**
 * @brief Adds a flag for every model error of the simulated world
 * (SimulatedWorldOptions: the anatomy's deformation, the segmentation
 * offset, the truth's resolution, the swelling) to `command`, stored into
 * `options`. All off by default.
 */
void addWorldOptions(CLI::App& command, SimulatedWorldOptions& options);

/**
 * @brief The simulated world of `model` on the airway of exactly one of
 * `mesh` and `ct` (a command's --mesh and --ct). Everything is checked
 * before anything is read: `model`, one of the two inputs, a model error
 * that needs the CT, then the display `command` (e.g. "vimlop simulate")
 * renders with (requireOffscreenRendering).
 * @throws vimlop::Error naming the first problem.
 */
SimulatedWorld loadSimulatedWorld(const std::string& mesh, const std::string& ct,
  const SimulatedWorldOptions& model, const std::string& command);

/**
 * @brief Adds --world ideal|clinical to `command`: every error source of
 * `settings` set at once (applyWorldPreset), applied when parsed so that the
 * flags of single sources override it.
 */
void addWorldPresetOption(CLI::App& command, WorldSettings& settings);

/**
 * @brief Adds --host, --port, --allow-remote, --max-clients,
 * --max-clients-per-address, --allow-client, --camera-name and
 * --per-frame-names to `command`, stored into `options` (which must outlive
 * the parse): where and how a pose server listens and names its devices.
 */
void addPoseServerOptions(CLI::App& command, PoseStreamServerOptions& options);

/**
 * @brief Adds --no-refinement, --refine-window, --refine-above-px,
 * --max-correction-mm and --max-correction-deg, stored into `refine` and
 * `options`: the refinement of tracked poses against the CT (`vimlop
 * track`, `evaluate tracking`).
 */
void addTrackingRefinementOptions(
  CLI::App& command, bool& refine, ContourWindowRefinementOptions& options);

/**
 * @brief Adds --max-features, --max-tracking-width-px, --inlier-px,
 * --tracker-offset-frames and --tracker-pull, stored into `options`, and
 * --tracker-max-lag-s, stored into `lag`: the frame-to-frame tracker and how
 * it uses an electromagnetic tracker (`vimlop track`, `evaluate tracking`).
 */
void addEndoscopeTrackerOptions(
  CLI::App& command, EndoscopeTrackerOptions& options, TrackerLagOptions& lag);

/**
 * @brief Adds --no-relocalisation, --degraded-above-px, --relocalise-search-mm
 * and --relocalise-search-deg, stored into `relocalise` and `options`: the
 * trust of tracked poses against the CT and the search after a loss
 * (`vimlop track`, `evaluate tracking`).
 */
void addTrackingRelocalisationOptions(
  CLI::App& command, bool& relocalise, ContourRelocalisationOptions& options);

/**
 * @brief addPoseServerOptions(), plus --duration-s and --allow-flagged: the
 * flags of every subcommand that serves a registration's poses
 * (VIMLOP::Server's servePoses).
 */
void addPoseServingOptions(CLI::App& command, PoseServingOptions& options);

/**
 * @brief What a pose server sends of a registration record: T, every frame's
 * camera-to-CT pose with its frame's time (when the record has them) and
 * the verdict of its confidence (when it has one).
 */
ServedPoses servedPosesOf(const RegistrationRecord& record);

/**
 * @brief For a command line whose command word names no command of `app`
 * (e.g. `vimlop regster`, `vimlop evaluate speeed`): the error to print,
 * suggesting the nearest command when the word is a likely typo; empty when
 * every command word is known (CLI11 would only say that a command is required).
 */
std::string unknownSubcommandMessage(const CLI::App& app, int argc, const char* const* argv);

/**
 * @brief The name of `names` nearest to `word` when `word` looks like a typo
 * of it (at most a third of it wrong, and 2 edits); empty otherwise.
 */
std::string nearestName(const std::string& word, const std::vector<std::string>& names);

/**
 * @brief A CLI11 parse error in words for `vimlop: error:` (exit code 1, as
 * every error); an error in the config file `configPath` (--config) names it.
 */
std::string parseErrorMessage(const CLI::ParseError& error, const std::string& configPath = "");

/**
 * @brief The words this program was started with (argv), set once by
 * main(): the command line a result folder records (joinCommandLine() in
 * Cohort/CommandLineWords.h).
 */
std::vector<std::string>& commandWords();

/// @brief Prints each of `lines` (a report's summaryLines) to stdout.
void printLines(const std::vector<std::string>& lines);

/**
 * @brief What a subcommand prints when it is done: its lines for a person,
 * and the same facts (numbers with their units in the key, paths written)
 * for a program, printed instead with `--json`.
 */
struct CommandSummary
{
  std::vector<std::string> lines;
  nlohmann::json json = nlohmann::json::object();
};

/**
 * @brief Adds `--json` to `command`, stored into `json`: the summary as JSON
 * on stdout and nothing else there (notes, warnings and progress go to
 * stderr as always).
 */
void addJsonFlag(CLI::App& command, bool& json);

/// @brief Prints the summary's lines to stdout, or with `json` its JSON alone.
void printSummary(const CommandSummary& summary, bool json);

/// @brief A camera's intrinsics as a summary's JSON says them: `width_px`,
/// `height_px`, `fx_px`, `fy_px`, `cx_px`, `cy_px`, `lens_model`, `distortion`.
nlohmann::json intrinsicsJson(const PinholeCamera& k);

/**
 * @brief Writes `json` to `path` through a temporary file and a rename, so an
 * interrupted run never leaves a half-written file.
 * @throws vimlop::Error if the file cannot be written.
 */
void writeJsonFile(const nlohmann::json& json, const std::string& path);

/**
 * @brief While it lives, Ctrl-C and SIGTERM ask the running command to stop
 * (requested() turns true) instead of ending the program, so that it can
 * stop its work cleanly; the previous handlers come back after.
 */
class InterruptGuard
{
public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  /// @brief Whether Ctrl-C or SIGTERM came since the guard was made.
  static bool requested();

private:
  void (*PreviousInt)(int) = nullptr;
  void (*PreviousTerm)(int) = nullptr;
};

/**
 * @brief Thrown by a subcommand to end the program with `code` after it has
 * said what it had to (e.g. 3: `vimlop register` flagged its result as a
 * failure; 130: interrupted).
 */
struct ExitRequest
{
  int code = 0;
};

} // namespace vimlop

#endif
