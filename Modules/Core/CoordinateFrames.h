#ifndef vimlop_CoordinateFrames_h
#define vimlop_CoordinateFrames_h

#include <Eigen/Core>

/**
 * @file CoordinateFrames.h
 * @brief The one place where VIMLOP's CT frame (ITK physical, LPS) meets RAS.
 *
 * LPS (x to the patient's left, y posterior, z superior) and RAS (x right,
 * y anterior, z superior) differ by the sign of x and y. VIMLOP works in LPS;
 * RAS appears at its edges only, e.g. in OpenIGTLink, whose transforms are
 * RAS by the protocol, and in 3D Slicer.
 */

namespace vimlop
{

/// @brief diag(-1, -1, 1, 1): maps LPS points to RAS points and back.
inline Eigen::Matrix4d lpsRasFlip()
{
  return Eigen::Vector4d(-1.0, -1.0, 1.0, 1.0).asDiagonal();
}

/**
 * @brief A transform into the CT frame, re-expressed into RAS: for a
 * camera-to-CT pose or an SfM-to-CT similarity M (both map *into* LPS),
 * lpsRasFlip() * M maps into RAS.
 */
inline Eigen::Matrix4d intoRas(const Eigen::Matrix4d& intoLps)
{
  return lpsRasFlip() * intoLps;
}

/**
 * @brief A transform into the CT frame (LPS) from a frame taken as it is
 * (e.g. a tracker's, whose numbers Slicer uses unchanged), read from the
 * ITK transform file 3D Slicer saved for its node A-to-RAS (e.g.
 * "TrackerToRAS", the tracker registered to the patient). Slicer writes the
 * inverse point map and takes both of its spaces as LPS
 * (Documentation/Exchange.md): the file holds F (A-to-RAS)^-1 F, with F =
 * lpsRasFlip(), and A-to-LPS, F (A-to-RAS), is the file's inverse times F.
 */
inline Eigen::Matrix4d intoLpsFromSlicerFile(const Eigen::Matrix4d& pointMapInFile)
{
  return pointMapInFile.inverse() * lpsRasFlip();
}

} // namespace vimlop

#endif
