#ifndef vimlop_LegacyVtkFileCheck_h
#define vimlop_LegacyVtkFileCheck_h

// Private to the Imaging module (not installed): a legacy VTK file judged
// before VTK's reader reads it. Throws vimlop::Error "'path': problem".
// VTK-free: plain file reading.

#include <string>

namespace vimlop::detail
{

/**
 * @brief Legacy VTK: the counts after POINTS, POLYGONS and the like at most
 * 20 000 000, and the points, cell lists and data-set field data walked as
 * VTK will read them: each cell's ids inside the list and naming points the
 * file has (VTK read past a list whose counts disagree), field arrays of
 * numbers with all their values (VTK dereferenced a null on others).
 */
void checkLegacyVtk(const std::string& path);

} // namespace vimlop::detail

#endif
