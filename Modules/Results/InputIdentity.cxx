#include <vimlop/Results/InputIdentity.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Core/Sha256.h>

#include <algorithm>
#include <filesystem>
#include <vector>

namespace vimlop
{

namespace fs = std::filesystem;

RegistrationRecord::InputFile identifyInput(const std::string& role, const std::string& path)
{
  std::error_code ec;
  if (!fs::exists(path, ec))
  {
    throwFileError(path, "no such file or folder to identify");
  }
  RegistrationRecord::InputFile input{ role, path, 0, std::string() };
  Sha256 digest;
  if (!fs::is_directory(path, ec))
  {
    input.bytes = digest.updateFromFile(path);
    input.sha256 = digest.hex();
    return input;
  }
  std::vector<std::string> files;
  for (fs::recursive_directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec))
  {
    if (it->is_regular_file())
    {
      files.push_back(fs::relative(it->path(), path).generic_string());
    }
  }
  if (ec)
  {
    throwFileError(path, "cannot list the folder to identify it (" + ec.message() + ")");
  }
  std::sort(files.begin(), files.end());
  for (const std::string& file : files)
  {
    digest.update(file.c_str(), file.size() + 1); // the name and its NUL
    input.bytes += digest.updateFromFile((fs::path(path) / file).string());
  }
  input.sha256 = digest.hex();
  return input;
}

std::vector<RegistrationRecord::InputFile> identifyInputs(
  const std::vector<std::pair<std::string, std::string>>& rolesAndPaths,
  std::vector<std::string>& problems)
{
  std::vector<RegistrationRecord::InputFile> inputs;
  for (const auto& [role, path] : rolesAndPaths)
  {
    if (path.empty())
    {
      continue;
    }
    try
    {
      inputs.push_back(identifyInput(role, path));
    }
    catch (const Error& e)
    {
      problems.push_back("cannot identify the " + role + " input: " + e.what());
      inputs.push_back({ role, path, 0, std::string() });
    }
  }
  return inputs;
}

std::string recordedInputPath(const RegistrationRecord& record, const std::string& role)
{
  for (const RegistrationRecord::InputFile& input : record.inputs)
  {
    std::error_code error;
    if (input.role == role && std::filesystem::exists(input.path, error))
    {
      return input.path;
    }
  }
  return "";
}

} // namespace vimlop
