#include "CommandLine.h"

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace vimlop
{

std::pair<double, double> parseRange(const std::string& text, const std::string& what)
{
  std::istringstream in(text);
  double a = 0.0;
  double b = 0.0;
  char comma = 0;
  const bool parsed = static_cast<bool>(in >> a >> comma >> b) && comma == ',';
  if (!parsed || !(in >> std::ws).eof())
  {
    throw Error(what + ": expected two numbers 'min,max', got '" + text + "'");
  }
  if (!(a >= 0.0) || !(a <= b) || !std::isfinite(b))
  {
    throw Error(what + ": need 0 <= min <= max, got '" + text + "'");
  }
  return { a, b };
}

std::vector<std::string> parseList(const std::string& text, const std::string& what)
{
  std::vector<std::string> items;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
  {
    if (item.empty())
    {
      throw Error(what + ": empty item in '" + text + "'");
    }
    items.push_back(item);
  }
  if (items.empty())
  {
    throw Error(what + ": no items given");
  }
  return items;
}

std::string joinNumbers(const std::vector<double>& numbers)
{
  std::ostringstream out;
  for (size_t i = 0; i < numbers.size(); ++i)
  {
    out << (i ? "," : "") << numbers[i];
  }
  return out.str();
}

std::string joinList(const std::vector<std::string>& items)
{
  std::string text;
  for (const std::string& item : items)
  {
    text += (text.empty() ? "" : ",") + item;
  }
  return text;
}

void addModelOptions(CLI::App& command, std::string& mesh, std::string& ct)
{
  CLI::Option* meshOption =
    command.add_option("--mesh", mesh, "airway surface (CT frame, normals into the air)");
  CLI::Option* ctOption =
    command.add_option("--ct", ct, "CT volume whose airway is segmented with the defaults");
  meshOption->excludes(ctOption);
}

void printLines(const std::vector<std::string>& lines)
{
  for (const std::string& line : lines)
  {
    std::printf("%s\n", line.c_str());
  }
}

void writeJsonFile(const nlohmann::json& json, const std::string& path)
{
  writeFileAtomically(path, json.dump(2) + "\n");
}

std::vector<double> parseNumbers(const std::string& text, const std::string& what)
{
  std::vector<double> numbers;
  for (const std::string& item : parseList(text, what))
  {
    try
    {
      size_t used = 0;
      numbers.push_back(std::stod(item, &used));
      if (used != item.size())
      {
        throw std::invalid_argument(item);
      }
    }
    catch (const std::exception&)
    {
      throw Error(what + ": '" + item + "' is not a number");
    }
  }
  return numbers;
}

} // namespace vimlop
