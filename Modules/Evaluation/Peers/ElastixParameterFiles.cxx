#include <vimlop/Evaluation/Peers/ElastixParameterFiles.h>

#include <dlfcn.h>

#include <filesystem>

namespace vimlop
{

std::string defaultElastixParametersFolder()
{
  namespace fs = std::filesystem;
  // The file holding this function: the shared library, or the program.
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&defaultElastixParametersFolder), &info) == 0 ||
    !info.dli_fname)
  {
    return VIMLOP_ELASTIX_INSTALLED_RELATIVE_DIR;
  }
  std::error_code ec;
  const fs::path here = fs::canonical(info.dli_fname, ec).parent_path();
  // The build tree's copy of the code runs from a folder fixed when CMake
  // configured the build; only there does the source tree count.
  if (!ec && fs::equivalent(here, VIMLOP_ELASTIX_BUILD_CODE_DIR, ec))
  {
    return VIMLOP_ELASTIX_SOURCE_DIR;
  }
  return (here / VIMLOP_ELASTIX_INSTALLED_RELATIVE_DIR).lexically_normal().string();
}

} // namespace vimlop
