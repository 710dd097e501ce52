#include <vimlop/Pipeline/StageTimings.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/TextFormat.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

namespace
{

/// Process CPU time (every thread), s. std::clock() is that on POSIX systems.
double processCpuS()
{
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

} // namespace

StageTimings::Stopwatch::Stopwatch()
  : WallStart(std::chrono::steady_clock::now())
  , CpuStartS(processCpuS())
{
}

double StageTimings::Stopwatch::wallS() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->WallStart).count();
}

double StageTimings::Stopwatch::cpuS() const
{
  // std::clock() can step back by a tick between threads' accounting: never negative.
  return std::max(0.0, processCpuS() - this->CpuStartS);
}

void StageTimings::set(const std::string& name, double wallS, double cpuS)
{
  if (name.empty())
  {
    throw Error("stage timings: a stage needs a name");
  }
  if (!std::isfinite(wallS) || !std::isfinite(cpuS) || wallS < 0.0 || cpuS < 0.0)
  {
    throw Error(formatText("stage timings: stage '%s' has a negative or non-finite time (wall "
                           "%g s, CPU %g s)",
      name.c_str(), wallS, cpuS));
  }
  for (Stage& s : this->Stages)
  {
    if (s.name == name)
    {
      s.wallS = wallS;
      s.cpuS = cpuS;
      return;
    }
  }
  this->Stages.push_back({ name, wallS, cpuS });
}

void StageTimings::set(const std::string& name, const Stopwatch& watch)
{
  this->set(name, watch.wallS(), watch.cpuS());
}

void StageTimings::remove(const std::string& name)
{
  this->Stages.erase(std::remove_if(this->Stages.begin(), this->Stages.end(),
                       [&](const Stage& s) { return s.name == name; }),
    this->Stages.end());
}

void StageTimings::append(const StageTimings& other)
{
  for (const Stage& s : other.Stages)
  {
    this->set(s.name, s.wallS, s.cpuS);
  }
  for (const Mark& m : other.Marks)
  {
    this->mark(m.name, m.atWallS);
  }
}

void StageTimings::mark(const std::string& name, double atWallS)
{
  if (name.empty())
  {
    throw Error("stage timings: a mark needs a name");
  }
  if (!std::isfinite(atWallS) || atWallS < 0.0)
  {
    throw Error(formatText(
      "stage timings: mark '%s' has a negative or non-finite time (%g s)", name.c_str(), atWallS));
  }
  for (Mark& m : this->Marks)
  {
    if (m.name == name)
    {
      m.atWallS = atWallS;
      return;
    }
  }
  this->Marks.push_back({ name, atWallS });
}

const StageTimings::Mark* StageTimings::findMark(const std::string& name) const
{
  for (const Mark& m : this->Marks)
  {
    if (m.name == name)
    {
      return &m;
    }
  }
  return nullptr;
}

const StageTimings::Stage* StageTimings::find(const std::string& name) const
{
  for (const Stage& s : this->Stages)
  {
    if (s.name == name)
    {
      return &s;
    }
  }
  return nullptr;
}

double StageTimings::totalWallS() const
{
  double sum = 0.0;
  for (const Stage& s : this->Stages)
  {
    sum += s.wallS;
  }
  return sum;
}

double StageTimings::totalCpuS() const
{
  double sum = 0.0;
  for (const Stage& s : this->Stages)
  {
    sum += s.cpuS;
  }
  return sum;
}

nlohmann::json StageTimings::toJson() const
{
  nlohmann::json stages = nlohmann::json::array();
  for (const Stage& s : this->Stages)
  {
    stages.push_back({ { "name", s.name }, { "wall_s", s.wallS }, { "cpu_s", s.cpuS } });
  }
  nlohmann::json json = { { "stages", stages }, { "total_wall_s", this->totalWallS() },
    { "total_cpu_s", this->totalCpuS() } };
  if (!this->Marks.empty())
  {
    nlohmann::json marks = nlohmann::json::array();
    for (const Mark& m : this->Marks)
    {
      marks.push_back({ { "name", m.name }, { "at_wall_s", m.atWallS } });
    }
    json["marks"] = marks;
  }
  return json;
}

StageTimings StageTimings::fromJson(const nlohmann::json& json, const std::string& source)
{
  const std::string where = "'" + source + "': stage timings: ";
  if (!json.is_object() || !json.contains("stages") || !json.at("stages").is_array())
  {
    throw Error(where + "expected an object with a list \"stages\"");
  }
  StageTimings timings;
  for (const nlohmann::json& s : json.at("stages"))
  {
    if (!s.is_object() || !s.contains("name") || !s.at("name").is_string() ||
      !s.contains("wall_s") || !s.at("wall_s").is_number() || !s.contains("cpu_s") ||
      !s.at("cpu_s").is_number())
    {
      throw Error(where + "each stage needs a \"name\", \"wall_s\" and \"cpu_s\"");
    }
    try
    {
      timings.set(
        s.at("name").get<std::string>(), s.at("wall_s").get<double>(), s.at("cpu_s").get<double>());
    }
    catch (const Error& e)
    {
      throwFileError(source, std::string(e.what()));
    }
  }
  if (!json.contains("marks"))
  {
    return timings;
  }
  if (!json.at("marks").is_array())
  {
    throw Error(where + "\"marks\" must be a list");
  }
  for (const nlohmann::json& m : json.at("marks"))
  {
    if (!m.is_object() || !m.contains("name") || !m.at("name").is_string() ||
      !m.contains("at_wall_s") || !m.at("at_wall_s").is_number())
    {
      throw Error(where + "each mark needs a \"name\" and \"at_wall_s\"");
    }
    try
    {
      timings.mark(m.at("name").get<std::string>(), m.at("at_wall_s").get<double>());
    }
    catch (const Error& e)
    {
      throwFileError(source, std::string(e.what()));
    }
  }
  return timings;
}

std::string StageTimings::summaryLine() const
{
  std::string line;
  for (const Stage& s : this->Stages)
  {
    line += formatText("%s%s %.2f s", line.empty() ? "" : ", ", s.name.c_str(), s.wallS);
  }
  line += formatText(
    "%s(total %.2f s, CPU %.2f s)", line.empty() ? "" : " ", this->totalWallS(), this->totalCpuS());
  for (const Mark& m : this->Marks)
  {
    line += formatText("; %s at %.2f s", m.name.c_str(), m.atWallS);
  }
  return line;
}

} // namespace vimlop
