#ifndef vimlop_ElastixParameterFiles_h
#define vimlop_ElastixParameterFiles_h

#include <string>

namespace vimlop
{

/**
 * @brief The folder of the elastix parameter files VIMLOP ships (affine.txt,
 * bspline.txt), used by P4 unless told otherwise.
 *
 * Installed, it is `<prefix>/share/vimlop/elastix`, found relative to the
 * installed Evaluation library (or to the program, when the library is
 * linked statically), so an installed VIMLOP never reads its source tree.
 * Running from the build tree, it is the source tree's Data/elastix. The
 * folder returned need not exist (elastix then reports the missing file).
 */
std::string defaultElastixParametersFolder();

} // namespace vimlop

#endif
