#include <vimlop/Results/PerturbationRuns.h>

#include <vimlop/Core/FileError.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace vimlop
{

std::vector<PerturbationRun> readPerturbationRuns(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    throwFileError(path, "no such file");
  }
  nlohmann::json j;
  std::ifstream in(path);
  try
  {
    in >> j;
  }
  catch (const nlohmann::json::exception& e)
  {
    throwFileError(path, std::string("not valid JSON (") + e.what() + ")");
  }
  if (!j.is_object() || !j.contains("runs") || !j.at("runs").is_array())
  {
    throwFileError(path, "no \"runs\" list (a perturbation study lists its runs)");
  }
  std::vector<PerturbationRun> runs;
  for (const nlohmann::json& r : j.at("runs"))
  {
    try
    {
      PerturbationRun run;
      run.offsetMm = r.at("offset_mm").get<double>();
      run.offsetDeg = r.value("offset_deg", 0.0);
      run.finalErrorMm = r.at("final_error_mm").get<double>();
      run.contourErrorPx = r.at("contour_error_px").get<double>();
      run.success = r.value("success", false);
      runs.push_back(run);
    }
    catch (const nlohmann::json::exception&)
    {
      throwFileError(path,
        "run " + std::to_string(runs.size()) +
          " needs numbers offset_mm, final_error_mm and contour_error_px");
    }
  }
  return runs;
}

void writePerturbationRuns(const std::vector<PerturbationRun>& runs, const std::string& path)
{
  nlohmann::json list = nlohmann::json::array();
  for (const PerturbationRun& run : runs)
  {
    list.push_back({ { "offset_mm", run.offsetMm }, { "offset_deg", run.offsetDeg },
      { "final_error_mm", run.finalErrorMm }, { "contour_error_px", run.contourErrorPx },
      { "success", run.success } });
  }
  std::ofstream out(path);
  out << nlohmann::json({ { "runs", list } }).dump(2) << "\n";
  if (!out)
  {
    throwFileError(path, "cannot write the file");
  }
}

} // namespace vimlop
