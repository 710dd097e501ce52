#include <vimlop/Video/StructureFromMotion.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Video/SfmReconstructor.h>

namespace vimlop
{

StructureFromMotion::StructureFromMotion()
  : StructureFromMotion(StructureFromMotionOptions())
{
}

StructureFromMotion::StructureFromMotion(const StructureFromMotionOptions& options)
  : Opts(options)
{
}

SfmReconstruction StructureFromMotion::reconstruct(const std::vector<cv::Mat>& frames,
  const PinholeCamera& intrinsics, const std::vector<std::string>& names, std::ostream* log) const
{
  if (frames.size() < 2)
  {
    throw Error("SfM needs at least 2 frames, got " + std::to_string(frames.size()));
  }
  intrinsics.validate();
  auto nameOf = [&](size_t i) { return i < names.size() ? names[i] : "frame" + std::to_string(i); };
  for (size_t i = 0; i < frames.size(); ++i)
  {
    if (frames[i].empty() || frames[i].depth() != CV_8U ||
      (frames[i].channels() != 1 && frames[i].channels() != 3))
    {
      throw Error("SfM: frame '" + nameOf(i) + "' is not an 8-bit grey or colour image");
    }
    if (frames[i].size() != frames[0].size())
    {
      throw Error("SfM: frame '" + nameOf(i) + "' is " + std::to_string(frames[i].cols) + "x" +
        std::to_string(frames[i].rows) + " but '" + nameOf(0) + "' is " +
        std::to_string(frames[0].cols) + "x" + std::to_string(frames[0].rows));
    }
  }
  if (intrinsics.widthPx != frames[0].cols || intrinsics.heightPx != frames[0].rows)
  {
    throw Error("SfM: the intrinsics are for " + std::to_string(intrinsics.widthPx) + "x" +
      std::to_string(intrinsics.heightPx) + " pixels but the frames are " +
      std::to_string(frames[0].cols) + "x" + std::to_string(frames[0].rows));
  }
  if (!this->FeatureMask.empty() &&
    (this->FeatureMask.type() != CV_8U || this->FeatureMask.cols != frames[0].cols ||
      this->FeatureMask.rows != frames[0].rows))
  {
    throw Error("SfM: the feature mask must be an 8-bit single-channel image of the frames' size");
  }
  detail::SfmReconstructor reconstructor(this->Opts, frames, intrinsics, log, this->FeatureMask);
  return reconstructor.run(names);
}

} // namespace vimlop
