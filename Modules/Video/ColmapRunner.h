#ifndef vimlop_ColmapRunner_h
#define vimlop_ColmapRunner_h

#include <vimlop/Core/PinholeCamera.h>

#include <string>

namespace vimlop
{

/// @brief The program and how hard it works.
struct ColmapRunnerOptions
{
  /// The COLMAP executable (default "colmap", looked up on the PATH).
  std::string executable = "colmap";
  /// Threads per step (default 2; -1 for all cores).
  int threads = 2;
  /// Least triangulation angle of COLMAP's initial pair, degrees (default
  /// 4; COLMAP's 16 suits wide-baseline photographs, not a scope that
  /// moves a few millimetres).
  double initialMinAngleDeg = 4.0;
  /// SIFT peak threshold (default 0.0017; COLMAP's 0.0067 finds a few dozen
  /// features on low-contrast mucosa, this about as many as the built-in SfM).
  double siftPeakThreshold = 0.0017;
  /// Runs of COLMAP's matching and mapping, at most (default 3), while one
  /// registers fewer than half of the frames; the run that registers the
  /// most is kept. Run n matches afresh and maps with random seed n: on the
  /// 12 frames of the P2 test about 1 run in 8 registered only 3 frames,
  /// and running the mapper alone again on the same matches gave the same 3.
  int mapperRuns = 3;
};

/**
 * @brief Runs the `colmap` program (COLMAP 3.x, e.g. Debian's package) on a
 * folder of frames: CPU SIFT extraction with the given pinhole intrinsics
 * (one camera, held fixed), exhaustive matching and incremental mapping
 * (both run again with another seed, up to `mapperRuns` times, while the
 * mapper registers fewer than half of the frames), and a text copy of the
 * model. Everything COLMAP prints goes
 * to `workFolder/colmap.log`, with a line for each mapper run that was not
 * enough; it runs headless (QT_QPA_PLATFORM=offscreen).
 */
class ColmapRunner
{
public:
  ColmapRunner();
  explicit ColmapRunner(const ColmapRunnerOptions& options);

  /// @brief True when the executable runs (`colmap help` succeeds).
  bool isAvailable() const;
  /// @throws vimlop::Error saying how to install COLMAP when it is not available.
  void requireAvailable() const;

  /**
   * @brief Reconstructs the images in `imageFolder` into `workFolder`
   * (created; database.db, sparse/0 in binary, sparse-text in text) and
   * returns the binary model folder.
   * @throws vimlop::Error when COLMAP is missing, `mapperRuns` is below 1, a
   * step fails (naming it and the log) or no mapper run gives a model.
   */
  std::string run(const std::string& imageFolder, const PinholeCamera& intrinsics,
    const std::string& workFolder) const;

  /// @brief The text copy of the model written by run().
  static std::string textModelFolder(const std::string& workFolder);

private:
  ColmapRunnerOptions Opts;
};

} // namespace vimlop

#endif
