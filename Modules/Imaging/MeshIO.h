#ifndef vimlop_MeshIO_h
#define vimlop_MeshIO_h

#include "VIMLOPImagingModule.h"

#include <vtkSmartPointer.h>

#include <string>

class vtkPolyData;

namespace vimlop
{

/**
 * @brief Reads a surface mesh: `.vtp`, `.vtk` (legacy polydata), `.stl`, `.ply`, `.obj`.
 * @throws vimlop::Error naming the file and the problem (missing, unsupported
 * extension, unreadable, no points).
 */
VIMLOPIMAGING_EXPORT vtkSmartPointer<vtkPolyData> readPolyData(const std::string& path);

/**
 * @brief Writes a surface mesh as `.vtp`, `.vtk`, `.stl` or `.ply` (binary);
 * a `.vtk` file's header says `SPACE=LPS`, the frame of VIMLOP's meshes, for 3D Slicer.
 * @throws vimlop::Error for an unsupported extension or a failed write.
 */
VIMLOPIMAGING_EXPORT void writePolyData(vtkPolyData* mesh, const std::string& path);

/// @brief True when `path` has an extension readPolyData() accepts.
VIMLOPIMAGING_EXPORT bool isMeshPath(const std::string& path);

/// @brief True when `path` has an extension writePolyData() accepts.
VIMLOPIMAGING_EXPORT bool isWritableMeshPath(const std::string& path);

} // namespace vimlop

#endif
