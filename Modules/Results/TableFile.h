#ifndef vimlop_TableFile_h
#define vimlop_TableFile_h

// Private to the Results module (not installed): how a result's tables are
// written, shared by the result folder and the tracking outputs.

#include <string>

class vtkTable;

namespace vimlop::detail
{

/// @brief Writes `table` as a binary VTK XML table (.vtt).
/// @throws vimlop::Error naming the file when it cannot be written.
void writeTableFile(vtkTable* table, const std::string& path);

} // namespace vimlop::detail

#endif
