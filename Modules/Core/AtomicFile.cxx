#include <vimlop/Core/AtomicFile.h>

#include <vimlop/Core/Error.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace vimlop
{

void writeFileAtomically(const std::string& path, const std::string& contents)
{
  const std::filesystem::path target(path);
  if (target.has_parent_path())
  {
    // A failure here shows as the write's failure below, which names the file.
    std::error_code ec;
    std::filesystem::create_directories(target.parent_path(), ec);
  }
  // Beside the target, so the rename stays on one file system and is atomic.
  const std::string temporary = path + ".part";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << contents;
    out.close();
    if (!out)
    {
      std::remove(temporary.c_str());
      throw Error("'" + path + "': cannot write the file");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, target, ec);
  if (ec)
  {
    std::remove(temporary.c_str());
    throw Error("'" + path + "': cannot write the file (" + ec.message() + ")");
  }
}

} // namespace vimlop
