#include <vimlop/Video/ColmapRunner.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Video/ColmapImport.h>

#include <cstdlib>
#include <filesystem>

namespace vimlop
{

namespace
{

namespace fs = std::filesystem;

/// Single quotes for /bin/sh, with embedded quotes escaped.
std::string quote(const std::string& s)
{
  std::string q = "'";
  for (char c : s)
  {
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return q + "'";
}

} // namespace

ColmapRunner::ColmapRunner()
  : ColmapRunner(ColmapRunnerOptions())
{
}

ColmapRunner::ColmapRunner(const ColmapRunnerOptions& options)
  : Opts(options)
{
}

bool ColmapRunner::isAvailable() const
{
  const std::string command =
    "QT_QPA_PLATFORM=offscreen " + quote(this->Opts.executable) + " help >/dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

std::string ColmapRunner::textModelFolder(const std::string& workFolder)
{
  return (fs::path(workFolder) / "sparse-text").string();
}

void ColmapRunner::requireAvailable() const
{
  if (!this->isAvailable())
  {
    throw Error(
      "COLMAP: cannot run '" + this->Opts.executable + "' (install Debian's 'colmap' package)");
  }
}

std::string ColmapRunner::run(
  const std::string& imageFolder, const PinholeCamera& k, const std::string& workFolder) const
{
  this->requireAvailable();
  std::error_code ec;
  fs::remove_all(workFolder, ec);
  fs::create_directories(fs::path(workFolder) / "sparse", ec);
  fs::create_directories(textModelFolder(workFolder), ec);
  if (ec)
  {
    throwFileError(workFolder, "cannot create the folder (" + ec.message() + ")");
  }
  const std::string database = (fs::path(workFolder) / "database.db").string();
  const std::string log = (fs::path(workFolder) / "colmap.log").string();
  const std::string threads = std::to_string(this->Opts.threads);
  const std::string exe = "QT_QPA_PLATFORM=offscreen " + quote(this->Opts.executable);
  const struct
  {
    const char* step;
    std::string arguments;
  } steps[] = {
    { "feature_extractor",
      "--database_path " + quote(database) + " --image_path " + quote(imageFolder) +
        " --ImageReader.camera_model PINHOLE --ImageReader.single_camera 1"
        " --ImageReader.camera_params " +
        quote(colmapPinholeParameters(k)) +
        " --SiftExtraction.use_gpu 0 --SiftExtraction.peak_threshold " +
        std::to_string(this->Opts.siftPeakThreshold) + " --SiftExtraction.num_threads " + threads },
    { "exhaustive_matcher",
      "--database_path " + quote(database) +
        " --SiftMatching.use_gpu 0 --SiftMatching.num_threads " + threads },
    { "mapper",
      "--database_path " + quote(database) + " --image_path " + quote(imageFolder) +
        " --output_path " + quote((fs::path(workFolder) / "sparse").string()) +
        " --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0"
        " --Mapper.ba_refine_extra_params 0 --Mapper.multiple_models 0"
        " --Mapper.init_min_tri_angle " +
        std::to_string(this->Opts.initialMinAngleDeg) + " --Mapper.num_threads " + threads },
    { "model_converter",
      "--input_path " + quote((fs::path(workFolder) / "sparse" / "0").string()) +
        " --output_path " + quote(textModelFolder(workFolder)) + " --output_type TXT" },
  };
  for (const auto& s : steps)
  {
    const std::string command =
      exe + " " + s.step + " " + s.arguments + " >>" + quote(log) + " 2>&1";
    if (std::system(command.c_str()) != 0)
    {
      throw Error(std::string("COLMAP: '") + s.step + "' failed (see '" + log + "')");
    }
    if (std::string(s.step) == "mapper" &&
      !fs::exists(fs::path(workFolder) / "sparse" / "0" / "cameras.bin", ec))
    {
      throw Error("COLMAP: the mapper reconstructed no model (see '" + log + "')");
    }
  }
  return (fs::path(workFolder) / "sparse" / "0").string();
}

} // namespace vimlop
