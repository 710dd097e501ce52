#ifndef vimlop_ColmapImport_h
#define vimlop_ColmapImport_h

#include <vimlop/Video/SfmReconstruction.h>

#include <string>
#include <vector>

namespace vimlop
{

/// @brief How a COLMAP sparse model is stored.
enum class ColmapFormat
{
  Automatic, ///< binary when `cameras.bin` exists, else text
  Text,      ///< cameras.txt, images.txt, points3D.txt
  Binary     ///< cameras.bin, images.bin, points3D.bin
};

/**
 * @brief Reads a COLMAP sparse model (a folder such as `sparse/0`) into an
 * SfmReconstruction.
 *
 * Camera models: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV,
 * OPENCV_FISHEYE and FULL_OPENCV (the ones used with endoscopes); their radial and
 * tangential coefficients become OpenCV distortion coefficients (k1, k2, p1,
 * p2; FULL_OPENCV's all eight, OpenCV's rational model), OPENCV_FISHEYE's a fisheye lens
 * (LensModel::Fisheye, k1..k4). COLMAP poses are world-to-camera (q, t) with the same camera axes
 * as OpenCV; they become camera-to-SfM poses. COLMAP puts the centre of the top-left pixel at (0.5,
 * 0.5), VIMLOP at (0, 0): principal points and observations are shifted by -0.5 px. Frames are the
 * model's images sorted by name (digit runs by value); when `frameNames` is given, frames follow it
 * instead, and names the model lacks become unregistered frames. Point covariances come from
 * triangulation geometry (COLMAP writes none) with an image noise of
 * `sigmaPx` pixels.
 *
 * @param warnings receives what was dropped (observations of unknown points,
 * track elements of unknown images, images not in `frameNames`).
 * @throws vimlop::Error naming the file and the problem: a missing file, an
 * unknown or unsupported camera model, an image of an unknown camera, a
 * point observed by an unknown image (dangling ids), a truncated or
 * malformed file.
 */
SfmReconstruction readColmapModel(const std::string& folder,
  ColmapFormat format = ColmapFormat::Automatic,
  const std::vector<std::string>& frameNames = std::vector<std::string>(), double sigmaPx = 0.5,
  std::vector<std::string>* warnings = nullptr);

/**
 * @brief COLMAP's camera parameters for `camera` as a PINHOLE model
 * ("fx,fy,cx,cy", with COLMAP's pixel-centre convention), for
 * `colmap feature_extractor --ImageReader.camera_params`.
 */
std::string colmapPinholeParameters(const PinholeCamera& camera);

} // namespace vimlop

#endif
