#include <vimlop/Pipeline/VideoRegistrationInputs.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

namespace vimlop
{

namespace
{

/// The text after `prefix` when `text` starts with it and has more, else nothing.
bool after(const std::string& text, const std::string& prefix, std::string& rest)
{
  if (text.size() <= prefix.size() || text.compare(0, prefix.size(), prefix) != 0)
  {
    return false;
  }
  rest = text.substr(prefix.size());
  return true;
}

} // namespace

void VideoRegistrationInputs::setStart(const std::string& text, const std::string& what)
{
  std::string path;
  if (after(text, "manual:", path))
  {
    this->startMode = StartMode::Manual;
  }
  else if (text != "canonical" && !after(text, "canonical:", path))
  {
    throw Error(
      what + ": expected manual:POSE.json, canonical or canonical:POSES.json, got '" + text + "'");
  }
  else
  {
    this->startMode = StartMode::Canonical;
  }
  this->startPosesPath = path;
}

void VideoRegistrationInputs::setStructureFromMotion(
  const std::string& text, const std::string& what)
{
  std::string folder;
  this->sfmFile.clear();
  this->runColmap = text == "colmap";
  if (text.size() > 5 && lowerCaseExtension(text) == ".json")
  {
    this->sfmFile = text;
  }
  else if (text != "builtin" && !this->runColmap && !after(text, "colmap:", folder))
  {
    throw Error(what + ": expected builtin, colmap, colmap:DIR or a file of vimlop sfm (.json), " +
      "got '" + text + "'");
  }
  this->colmapFolder = folder;
}

} // namespace vimlop
