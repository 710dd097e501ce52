#ifndef vimlop_VtkXmlFileCheck_h
#define vimlop_VtkXmlFileCheck_h

// Private to the Imaging module (not installed): a VTK XML file's binary
// arrays judged before VTK's XML reader reads them. Throws vimlop::Error
// "'path': problem". VTK-free: plain file reading.

#include <string>

namespace vimlop::detail
{

/// @brief VTK XML polydata: the counts of the Piece elements at most 20 000 000.
void checkXmlPolyData(const std::string& path);

/**
 * @brief The header of every binary array of a VTK XML file (inline base64 or
 * appended, raw or base64, compressed or not) fits in the bytes the array has:
 * VTK 9.1's reader allocates the block count a compressed array's header
 * claims (16 GB from a 4 KB file) and the block size it claims before it
 * reads them. The file's header type must be UInt32 or UInt64, and a block
 * at most 64 MiB decoded.
 */
void checkXmlArrays(const std::string& path);

} // namespace vimlop::detail

#endif
