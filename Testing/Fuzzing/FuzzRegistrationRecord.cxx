// Fuzzes the reading of result folders through their result.json. The VTK
// files of the folder are written once, from a small record made here, and
// stay valid; each input replaces result.json. The seed corpus holds the
// result.json of that record (regenerate it with VIMLOP_FUZZ_WRITE_SEED=path).
#include "FuzzTemporaryFile.h"
#include <vimlop/Core/Error.h>
#include <vimlop/Results/RegistrationRecordIO.h>

#include <vtkObject.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace
{

vimlop::RegistrationRecord makeRecord()
{
  using Eigen::Vector3d;
  vimlop::RegistrationRecord record;
  record.source = "fuzz fixture";
  // A tetrahedron with outward faces, 10 mm across.
  record.model = vimlop::TriangleMesh(
    { Vector3d(0, 0, 0), Vector3d(10, 0, 0), Vector3d(0, 10, 0), Vector3d(0, 0, 10) },
    { Eigen::Vector3i(0, 2, 1), Eigen::Vector3i(0, 1, 3), Eigen::Vector3i(0, 3, 2),
      Eigen::Vector3i(1, 2, 3) });
  for (int i = 0; i < 3; ++i)
  {
    record.data.points.emplace_back(1.0 + i, 1.0, 1.0);
    record.data.pointCovariances.push_back(0.25 * Eigen::Matrix3d::Identity());
  }
  vimlop::VideoFrame frame;
  frame.frameId = 7;
  frame.intrinsics.fx = frame.intrinsics.fy = 100.0;
  frame.intrinsics.cx = frame.intrinsics.cy = 50.0;
  frame.intrinsics.widthPx = frame.intrinsics.heightPx = 100;
  frame.contour.push_back({ Eigen::Vector2d(10, 20), Eigen::Vector2d(1, 0) });
  frame.contour.push_back({ Eigen::Vector2d(11, 20), Eigen::Vector2d(0, 1) });
  record.data.frames.push_back(frame);
  vimlop::RegistrationResult& result = record.result;
  result.termination = vimlop::TerminationReason::Converged;
  result.iterations = 1;
  vimlop::IterationRecord iteration;
  iteration.iteration = 1;
  result.history.push_back(iteration);
  for (const Vector3d& x : record.data.points)
  {
    result.pointInliers.push_back(1);
    result.pointMatches.push_back(x);
  }
  vimlop::FrameResult f;
  f.frameId = frame.frameId;
  f.contourPoints = 2;
  vimlop::ContourCorrespondence c;
  c.videoPixel = Eigen::Vector2d(10, 20);
  c.modelPixel = Eigen::Vector2d(10.5, 20);
  f.correspondences.push_back(c);
  result.frames.push_back(f);
  record.truth = vimlop::RegistrationRecord::GroundTruth{ vimlop::SimilarityTransform(),
    { vimlop::CameraPose() }, { Vector3d(1, 1, 1) } };
  return record;
}

std::string folder;

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  vtkObject::GlobalWarningDisplayOff(); // the reader reports errors itself
  folder = vimlop::fuzzing::temporaryFolder("result");
  vimlop::writeRegistrationRecord(makeRecord(), folder);
  if (const char* seed = std::getenv("VIMLOP_FUZZ_WRITE_SEED"))
  {
    std::filesystem::copy_file(
      folder + "/result.json", seed, std::filesystem::copy_options::overwrite_existing);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  vimlop::fuzzing::writeFile(
    folder + "/result.json", std::string_view(reinterpret_cast<const char*>(data), size));
  try
  {
    const vimlop::RegistrationRecord record = vimlop::readRegistrationRecord(folder);
    // An accepted result holds no NaN in what reports draw.
    if (!record.result.sfmToCT.matrix().allFinite())
    {
      std::abort();
    }
  }
  catch (const vimlop::Error&)
  {
  }
  return 0;
}
