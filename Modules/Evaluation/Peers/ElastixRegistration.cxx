#include <vimlop/Evaluation/Peers/ElastixRegistration.h>

#include <vimlop/Core/ChildProcess.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Imaging/CTVolumeIO.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace vimlop
{

namespace
{

/// Runs a program with its stdout and stderr into `log`; returns its exit
/// code (-1 when a signal ended it) and the wall time.
int run(const std::vector<std::string>& arguments, const std::string& log, double& seconds)
{
  const ChildProcessResult result = runChildProcess(arguments, log, log);
  seconds = result.wallS;
  return result.exitCode;
}

/// The "OutputPoint = [ x y z ]" of each line of transformix's outputpoints.txt.
std::vector<std::array<double, 3>> readOutputPoints(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throwFileError(path, "transformix wrote no output points");
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
      throwFileError(path, "unreadable output point: " + line);
    }
    points.push_back(p);
  }
  return points;
}

} // namespace

bool ElastixRegistration::available(const ElastixRegistrationOptions& options)
{
  for (const std::string& program : { options.elastix, options.transformix })
  {
    try
    {
      if (runChildProcess({ program, "--version" }, "/dev/null", "/dev/null").exitCode != 0)
      {
        return false;
      }
    }
    catch (const Error&)
    {
      return false; // not installed, or not a program
    }
  }
  return true;
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
      throwFileError(file, "no such elastix parameter file");
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
  std::vector<std::string> command = { options.elastix, "-f", fixedPath, "-m", movingPath, "-out",
    dir.string() };
  for (const std::string& file : options.parameterFiles)
  {
    command.insert(command.end(), { "-p", file });
  }
  if (options.threads > 0)
  {
    command.insert(command.end(), { "-threads", std::to_string(options.threads) });
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
  if (run({ options.transformix, "-def", pointsPath, "-tp", transform, "-out", dir.string() },
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
