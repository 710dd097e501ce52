#include "CommandLine.h"

#include <vimlop/Core/AtomicFile.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/PinholeCamera.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
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

std::vector<std::string>& commandWords()
{
  static std::vector<std::string> words;
  return words;
}

void printLines(const std::vector<std::string>& lines)
{
  for (const std::string& line : lines)
  {
    std::printf("%s\n", line.c_str());
  }
}

void addJsonFlag(CLI::App& command, bool& json)
{
  command.add_flag("--json", json,
    "print the summary as JSON (machine-readable) on stdout, and nothing else there");
}

void printSummary(const CommandSummary& summary, bool json)
{
  if (json)
  {
    std::printf("%s\n", summary.json.dump(2).c_str());
    return;
  }
  printLines(summary.lines);
}

nlohmann::json intrinsicsJson(const PinholeCamera& k)
{
  return { { "width_px", k.widthPx }, { "height_px", k.heightPx }, { "fx_px", k.fx },
    { "fy_px", k.fy }, { "cx_px", k.cx }, { "cy_px", k.cy },
    { "lens_model", k.lensModel == LensModel::Fisheye ? "fisheye" : "radial-tangential" },
    { "distortion",
      std::vector<double>(k.distortion.data(), k.distortion.data() + k.distortion.size()) } };
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

namespace
{

/// Edits (insertions, deletions, substitutions) that turn `a` into `b`.
size_t editDistance(const std::string& a, const std::string& b)
{
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j)
  {
    row[j] = j;
  }
  for (size_t i = 1; i <= a.size(); ++i)
  {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
    {
      const size_t above = row[j];
      row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1]) });
      diagonal = above;
    }
  }
  return row[b.size()];
}

} // namespace

std::string unknownSubcommandMessage(const CLI::App& app, int argc, const char* const* argv)
{
  const CLI::App* command = &app;
  std::string path = "vimlop";
  for (int i = 1; i < argc; ++i)
  {
    const std::string word = argv[i];
    const std::vector<const CLI::App*> children =
      command->get_subcommands([](const CLI::App*) { return true; });
    if (word.empty() || word[0] == '-' || children.empty())
    {
      return std::string(); // options, or a command without subcommands: CLI11 checks them
    }
    const CLI::App* match = nullptr;
    std::vector<std::string> names;
    for (const CLI::App* child : children)
    {
      match = child->get_name() == word ? child : match;
      names.push_back(child->get_name());
    }
    if (!match)
    {
      const std::string near = nearestName(word, names);
      return "'" + word + "' is not a command of " + path +
        (near.empty() ? std::string() : "; did you mean '" + near + "'?") + " (" + path +
        " --help lists them)";
    }
    command = match;
    path += " " + word;
  }
  return std::string();
}

std::string nearestName(const std::string& word, const std::vector<std::string>& names)
{
  std::string nearest;
  size_t nearestDistance = word.size();
  for (const std::string& name : names)
  {
    const size_t distance = editDistance(word, name);
    if (distance < nearestDistance)
    {
      nearest = name;
      nearestDistance = distance;
    }
  }
  // At most a third of the word wrong (and 2 edits): a typo, not another word.
  return !nearest.empty() && nearestDistance <= std::max<size_t>(2, word.size() / 3) ? nearest : "";
}

namespace
{
std::atomic<bool> interruptRequested{ false };
}

InterruptGuard::InterruptGuard()
{
  interruptRequested = false;
  this->PreviousInt = std::signal(SIGINT, [](int) { interruptRequested = true; });
  this->PreviousTerm = std::signal(SIGTERM, [](int) { interruptRequested = true; });
}

InterruptGuard::~InterruptGuard()
{
  std::signal(SIGINT, this->PreviousInt);
  std::signal(SIGTERM, this->PreviousTerm);
}

bool InterruptGuard::requested()
{
  return interruptRequested;
}

std::string parseErrorMessage(const CLI::ParseError& error, const std::string& configPath)
{
  const std::string text = error.what();
  // A config file's problems name the file and say what is wrong in it.
  const std::string unparsed = "INI was not able to parse ";
  if (dynamic_cast<const CLI::ConfigError*>(&error) && text.rfind(unparsed, 0) == 0)
  {
    const std::string item = text.substr(unparsed.size());
    const size_t dot = item.rfind('.');
    std::string problem;
    if (item.size() > 3 && item.compare(item.size() - 3, 3, ".++") == 0)
    {
      problem = "no command is named [" + item.substr(0, item.size() - 3) + "]";
    }
    else if (dot != std::string::npos && item.find(' ') == std::string::npos)
    {
      problem = "[" + item.substr(0, dot) + "] has no option '" + item.substr(dot + 1) + "'";
    }
    else
    {
      problem = "cannot read '" + item + "' (lines are 'name = value', under a [command] section)";
    }
    return "'" + configPath + "': " + problem;
  }
  if (dynamic_cast<const CLI::FileError*>(&error) && !configPath.empty())
  {
    return "'" + configPath + "': cannot read the config file (is it there?)";
  }
  return (text == "A subcommand is required" ? std::string("give a command") : text) +
    " (--help lists the commands and options)";
}

} // namespace vimlop
