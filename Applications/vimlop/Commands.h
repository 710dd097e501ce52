#ifndef vimlop_Commands_h
#define vimlop_Commands_h

/**
 * @file Commands.h
 * @brief The subcommands of `vimlop`, each in its own file, which main.cxx
 * adds.
 */

namespace CLI
{
class App;
}

namespace vimlop
{

/// @brief Adds `vimlop canonical`: canonical camera poses along a (template) airway (V13 b).
void addCanonicalCommand(CLI::App& app);

/// @brief `vimlop calibrate`: the camera's intrinsics from views of a chessboard.
void addCalibrateCommand(CLI::App& app);
/**
 * @brief Adds `vimlop cohort run|submit|status|resubmit|merge|task`: a
 * manifest's rows run on this machine or as Slurm job arrays, and merged.
 */
void addCohortCommand(CLI::App& app);
/// @brief Adds `vimlop contours`: occluding contours with normals in every frame of a sequence.
void addContoursCommand(CLI::App& app);
/**
 * @brief Adds `vimlop evaluate <protocol>` with P1-P3; returns it so that
 * other protocols can add themselves.
 */
CLI::App* addEvaluateCommand(CLI::App& app);
/// @brief Adds `warp` (protocol P4, template warp) to the `vimlop evaluate` group.
void addEvaluateWarpCommand(CLI::App& evaluate);
/// @brief Adds `budget` (protocol P5, the error budget) to the `vimlop evaluate` group.
void addEvaluateBudgetCommand(CLI::App& evaluate);
/**
 * @brief Adds `speed` (the main job's speed benchmark, issue 22) to the
 * `vimlop evaluate` group.
 */
void addEvaluateSpeedCommand(CLI::App& evaluate);
/**
 * @brief Adds `vimlop export`: a result folder as a 3D Slicer scene and ITK
 * transform files (SlicerSceneExport.h).
 */
void addExportCommand(CLI::App& app);
/// @brief Adds `vimlop info <file>`: what a CT, mesh or intrinsics file holds.
void addInfoCommand(CLI::App& app);
/**
 * @brief Adds `vimlop register`, the main job: flags over
 * VideoRegistrationPipeline, then the result folder, the summary and,
 * with --serve, the poses over OpenIGTLink.
 */
void addRegisterCommand(CLI::App& app);
/// @brief Adds `vimlop report`: the rendered report of a result folder and/or a perturbation study.
void addReportCommand(CLI::App& app);
/// @brief Adds `vimlop segment`: the nasal airway surface of a head CT.
void addSegmentCommand(CLI::App& app);
/// @brief Adds `vimlop serve`: the camera poses of a pose file or a result folder to
/// navigation software over OpenIGTLink (serving itself is in PoseServing.h).
void addServeCommand(CLI::App& app);
/// @brief Adds `vimlop sfm`: structure from motion of a sequence (built in, or a COLMAP import).
void addSfmCommand(CLI::App& app);
/// @brief Adds `vimlop simulate`: a virtual endoscope sequence in the airway of a CT.
void addSimulateCommand(CLI::App& app);
/// @brief Adds `vimlop track`: the pose of every frame after a registration (EndoscopeTracker).
void addTrackCommand(CLI::App& app);
/// @brief Adds `vimlop warp`: template CT to patient CT, with meshes and poses carried over.
void addWarpCommand(CLI::App& app);

} // namespace vimlop

#endif
