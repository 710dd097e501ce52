#include <vimlop/Evaluation/Peers/ElastixRegistration.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Imaging/CTVolumeIO.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace vimlop
{

namespace
{

/// Single quotes for /bin/sh (the paths may hold spaces).
std::string quoted(const std::string& text)
{
  std::string out = "'";
  for (char c : text)
  {
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return out + "'";
}

/// Runs a shell command with its output into `log`; returns the exit status and the wall time.
int run(const std::string& command, const std::string& log, double& seconds)
{
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system((command + " > " + quoted(log) + " 2>&1").c_str());
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return status;
}

/// The "OutputPoint = [ x y z ]" of each line of transformix's outputpoints.txt.
std::vector<std::array<double, 3>> readOutputPoints(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw Error("'" + path + "': transformix wrote no output points");
  }
  std::vector<std::array<double, 3>> points;
  std::string line;
  while (std::getline(in, line))
  {
    const auto at = line.find("OutputPoint = [");
    if (at == std::string::npos)
    {
      continue;
    }
    std::istringstream values(line.substr(at + 15));
    std::array<double, 3> p{};
    if (!(values >> p[0] >> p[1] >> p[2]))
    {
      throw Error("'" + path + "': unreadable output point: " + line);
    }
    points.push_back(p);
  }
  return points;
}

} // namespace

bool ElastixRegistration::available(const ElastixRegistrationOptions& options)
{
  const std::string quiet = " > /dev/null 2>&1";
  return std::system((quoted(options.elastix) + " --version" + quiet).c_str()) == 0 &&
    std::system((quoted(options.transformix) + " --version" + quiet).c_str()) == 0;
}

ElastixRegistration ElastixRegistration::compute(const CTVolume& fixed, const CTVolume& moving,
  const std::vector<std::array<double, 3>>& fixedPoints, const ElastixRegistrationOptions& options)
{
  if (options.parameterFiles.empty() || options.workDirectory.empty())
  {
    throw Error("elastix needs at least one parameter file and a work folder");
  }
  for (const std::string& file : options.parameterFiles)
  {
    if (!std::filesystem::is_regular_file(file))
    {
      throw Error("'" + file + "': no such elastix parameter file");
    }
  }
  namespace fs = std::filesystem;
  const fs::path dir(options.workDirectory);
  fs::create_directories(dir);
  const std::string fixedPath = (dir / "fixed.mha").string();
  const std::string movingPath = (dir / "moving.mha").string();
  writeCTVolume(fixed, fixedPath);
  writeCTVolume(moving, movingPath);

  ElastixRegistration result;
  std::string command = quoted(options.elastix) + " -f " + quoted(fixedPath) + " -m " +
    quoted(movingPath) + " -out " + quoted(dir.string());
  for (const std::string& file : options.parameterFiles)
  {
    command += " -p " + quoted(file);
  }
  if (options.threads > 0)
  {
    command += " -threads " + std::to_string(options.threads);
  }
  const std::string elastixLog = (dir / "elastix-console.txt").string();
  if (run(command, elastixLog, result.registrationSeconds) != 0)
  {
    throw Error("elastix failed (see '" + elastixLog + "')");
  }

  const std::string pointsPath = (dir / "fixed-points.txt").string();
  {
    std::ofstream points(pointsPath);
    points << "point\n" << fixedPoints.size() << "\n";
    points.precision(10);
    for (const auto& p : fixedPoints)
    {
      points << p[0] << " " << p[1] << " " << p[2] << "\n";
    }
  }
  // The last stage's transform parameters chain to the earlier ones.
  const std::string transform =
    (dir / ("TransformParameters." + std::to_string(options.parameterFiles.size() - 1) + ".txt"))
      .string();
  const std::string transformixLog = (dir / "transformix-console.txt").string();
  if (run(quoted(options.transformix) + " -def " + quoted(pointsPath) + " -tp " +
          quoted(transform) + " -out " + quoted(dir.string()),
        transformixLog, result.transformSeconds) != 0)
  {
    throw Error("transformix failed (see '" + transformixLog + "')");
  }
  result.movingPoints = readOutputPoints((dir / "outputpoints.txt").string());
  if (result.movingPoints.size() != fixedPoints.size())
  {
    throw Error("transformix returned " + std::to_string(result.movingPoints.size()) +
      " points for " + std::to_string(fixedPoints.size()));
  }
  return result;
}

} // namespace vimlop
