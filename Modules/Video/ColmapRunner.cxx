#include <vimlop/Video/ColmapRunner.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Video/ColmapBinaryModel.h>
#include <vimlop/Video/ColmapImport.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>

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

/// Regular files in `folder`: the frames COLMAP reads.
std::uint64_t imageFiles(const std::string& folder)
{
  std::uint64_t n = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(folder))
  {
    n += e.is_regular_file();
  }
  return n;
}

/// Images registered in a binary COLMAP model, 0 without a model.
std::uint64_t registeredImages(const fs::path& model)
{
  const fs::path images = model / "images.bin";
  std::error_code ec;
  if (!fs::exists(images, ec))
  {
    return 0;
  }
  detail::ColmapModel read;
  detail::readImagesBinary(images.string(), read);
  return read.images.size();
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
  if (this->Opts.mapperRuns < 1)
  {
    throw Error("COLMAP: the mapper must run at least once, got " +
      std::to_string(this->Opts.mapperRuns) + " runs");
  }
  this->requireAvailable();
  std::error_code ec;
  fs::remove_all(workFolder, ec);
  fs::create_directories(fs::path(workFolder) / "sparse", ec);
  fs::create_directories(textModelFolder(workFolder), ec);
  if (ec)
  {
    throwFileError(workFolder, "cannot create the folder (" + ec.message() + ")");
  }
  const fs::path model = fs::path(workFolder) / "sparse" / "0";
  const fs::path bestModel = fs::path(workFolder) / "sparse-best";
  const std::string database = (fs::path(workFolder) / "database.db").string();
  const std::string log = (fs::path(workFolder) / "colmap.log").string();
  const std::string threads = std::to_string(this->Opts.threads);
  const std::string exe = "QT_QPA_PLATFORM=offscreen " + quote(this->Opts.executable);
  const auto step = [&](const char* name, const std::string& arguments)
  {
    const std::string command = exe + " " + name + " " + arguments + " >>" + quote(log) + " 2>&1";
    if (std::system(command.c_str()) != 0)
    {
      throw Error(std::string("COLMAP: '") + name + "' failed (see '" + log + "')");
    }
  };
  step("feature_extractor",
    "--database_path " + quote(database) + " --image_path " + quote(imageFolder) +
      " --ImageReader.camera_model PINHOLE --ImageReader.single_camera 1"
      " --ImageReader.camera_params " +
      quote(colmapPinholeParameters(k)) +
      " --SiftExtraction.use_gpu 0 --SiftExtraction.peak_threshold " +
      std::to_string(this->Opts.siftPeakThreshold) + " --SiftExtraction.num_threads " + threads);
  const std::uint64_t frames = imageFiles(imageFolder);
  std::uint64_t best = 0;
  for (int run = 1; run <= this->Opts.mapperRuns && 2 * best < frames; ++run)
  {
    // Each run matches and maps with its own seed: the mapper is
    // deterministic on a given database, and a bad two-view geometry from
    // the matcher's RANSAC can start it from a degenerate pair.
    const std::string seed = " --random_seed " + std::to_string(run);
    if (run > 1)
    {
      step("database_cleaner", "--database_path " + quote(database) + " --type matches");
    }
    step("exhaustive_matcher",
      "--database_path " + quote(database) +
        " --SiftMatching.use_gpu 0 --SiftMatching.num_threads " + threads + seed);
    fs::remove_all(model, ec);
    step("mapper",
      "--database_path " + quote(database) + " --image_path " + quote(imageFolder) + seed +
        " --output_path " + quote((fs::path(workFolder) / "sparse").string()) +
        " --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0"
        " --Mapper.ba_refine_extra_params 0 --Mapper.multiple_models 0"
        " --Mapper.init_min_tri_angle " +
        std::to_string(this->Opts.initialMinAngleDeg) + " --Mapper.num_threads " + threads);
    const std::uint64_t registered = registeredImages(model);
    if (registered > best)
    {
      best = registered;
      fs::remove_all(bestModel, ec);
      fs::rename(model, bestModel, ec);
      if (ec)
      {
        throwFileError(model.string(), "cannot move the model (" + ec.message() + ")");
      }
    }
    if (2 * best < frames)
    {
      std::ofstream(log, std::ios::app)
        << "vimlop: mapper run " << run << " of " << this->Opts.mapperRuns << " registered "
        << registered << " of " << frames << " frames\n";
    }
  }
  if (best == 0)
  {
    throw Error("COLMAP: the mapper reconstructed no model (see '" + log + "')");
  }
  fs::remove_all(model, ec);
  fs::rename(bestModel, model, ec);
  if (ec)
  {
    throwFileError(bestModel.string(), "cannot move the model (" + ec.message() + ")");
  }
  step("model_converter",
    "--input_path " + quote(model.string()) + " --output_path " +
      quote(textModelFolder(workFolder)) + " --output_type TXT");
  return model.string();
}

} // namespace vimlop
