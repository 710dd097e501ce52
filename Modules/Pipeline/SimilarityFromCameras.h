#ifndef vimlop_SimilarityFromCameras_h
#define vimlop_SimilarityFromCameras_h

#include <vimlop/Core/CameraPose.h>
#include <vimlop/Core/SimilarityTransform.h>
#include <vimlop/Video/SfmReconstruction.h>

#include <vector>

namespace vimlop
{

/**
 * @brief The SfM-to-CT similarity that best carries the registered SfM
 * cameras onto `camerasCT` (one per SfM frame, in the order of `sfm.frames`;
 * those of unregistered frames are ignored): the rotation is the chordal mean
 * of R_CT R_SfMᵀ over the frames (the centres of a path along a passage are
 * nearly collinear and would leave the roll about it undetermined), then the
 * least-squares scale and translation of the centres. What a known truth
 * (a simulation's poses, `vimlop register --truth`) says T should be.
 * @throws vimlop::Error when the lists differ in length or fewer than two
 * frames are registered.
 */
SimilarityTransform similarityFromCameras(
  const SfmReconstruction& sfm, const std::vector<CameraPose>& camerasCT);

} // namespace vimlop

#endif
