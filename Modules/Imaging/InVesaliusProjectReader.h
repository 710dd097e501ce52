#ifndef vimlop_InVesaliusProjectReader_h
#define vimlop_InVesaliusProjectReader_h

#include <vimlop/Imaging/CTVolume.h>

#include "VIMLOPImagingModule.h"

#include <string>

namespace vimlop
{

/**
 * @brief Reads the CT volume of an InVesalius 3 project (`.inv3`).
 *
 * An `.inv3` file is a gzip-compressed tar archive holding `main.plist` (an
 * XML property list) and the raw volume it names under `matrix` (`matrix.dat`:
 * little-endian int16 Hounsfield units, C order with shape (z, y, x)), with the
 * voxel size under `spacing` as (x, y, z) in mm.
 *
 * The project stores no patient orientation. InVesalius flips the rows of the
 * axial slices when it imports DICOM, so in the stored matrix y grows towards
 * the patient's anterior and z towards superior; columns are assumed to grow
 * towards the patient's left as in standard axial DICOM. In LPS that gives the
 * direction diag(1, -1, 1); the origin is put where index (0, ny - 1, 0) maps to
 * (0, 0, 0), so all coordinates are non-negative. (Checked on Debian's
 * invesalius-examples Cranium.inv3: the face is at high y, the vertex at high z.)
 *
 * @throws vimlop::Error naming the file and the problem when the archive is
 * unreadable, `main.plist` or the matrix is missing, or sizes disagree.
 */
VIMLOPIMAGING_EXPORT CTVolume readInVesaliusProject(const std::string& path);

} // namespace vimlop

#endif
