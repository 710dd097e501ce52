#ifndef vimlop_PolyDataConversion_h
#define vimlop_PolyDataConversion_h

#include <vimlop/Core/TriangleMesh.h>

#include "VIMLOPImagingModule.h"

#include <vtkSmartPointer.h>

class vtkPolyData;

namespace vimlop
{

/**
 * @brief The triangles of `polyData` as a TriangleMesh (same frame and units).
 *
 * Polygons with more than three corners are triangulated; vertices, lines
 * and strips are ignored. Face order (hence normal direction) is kept.
 * @throws vimlop::Error if there are no polygons.
 */
VIMLOPIMAGING_EXPORT TriangleMesh toTriangleMesh(vtkPolyData* polyData);

/// @brief A polydata with the mesh's points, triangles and face normals ("Normals").
VIMLOPIMAGING_EXPORT vtkSmartPointer<vtkPolyData> toPolyData(const TriangleMesh& mesh);

} // namespace vimlop

#endif
