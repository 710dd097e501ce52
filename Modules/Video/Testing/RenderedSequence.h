#ifndef vimlop_RenderedSequence_h
#define vimlop_RenderedSequence_h

// A short virtual-endoscope sequence in a folded tube, rendered once per test
// program, with its ground truth (needs an X display).

#include "TestMeshes.h"
#include <vimlop/Core/RegistrationModel.h>
#include <vimlop/Rendering/EndoscopeTrajectory.h>
#include <vimlop/Rendering/vtkVIMLOPVirtualEndoscope.h>

#include <opencv2/core/mat.hpp>

#include <vtkNew.h>

#include <memory>
#include <string>
#include <vector>

namespace vimlop::fixtures
{

/// A short sequence in a folded tube, rendered once for all tests.
struct Sequence
{
  TriangleMesh mesh;
  std::unique_ptr<RegistrationModel> model;
  PinholeCamera intrinsics;
  std::vector<CameraPose> poses;
  std::vector<cv::Mat> frames;
  std::vector<DepthMap> depth;
  std::vector<std::string> names;
};

inline const Sequence& sequence()
{
  static const Sequence s = []
  {
    Sequence s;
    s.mesh = fixtures::makeTube(4.0, 60.0, 0.35);
    s.model = std::make_unique<RegistrationModel>(s.mesh);
    s.intrinsics.fx = s.intrinsics.fy = 200.0;
    s.intrinsics.cx = 159.5;
    s.intrinsics.cy = 119.5;
    s.intrinsics.widthPx = 320;
    s.intrinsics.heightPx = 240;
    EndoscopeTrajectoryOptions path;
    path.frames = 16;
    path.intrinsics = s.intrinsics;
    path.minContourSamples = 50;
    s.poses = makeEndoscopeTrajectory(*s.model, path, 2);
    vtkNew<vtkVIMLOPVirtualEndoscope> endoscope;
    endoscope->SetMesh(s.mesh);
    for (size_t f = 0; f < s.poses.size(); ++f)
    {
      const EndoscopeImage image = endoscope->Render(s.intrinsics, s.poses[f], f);
      cv::Mat bgr(image.heightPx, image.widthPx, CV_8UC3);
      for (int v = 0; v < image.heightPx; ++v)
      {
        for (int u = 0; u < image.widthPx; ++u)
        {
          bgr.at<cv::Vec3b>(v, u) =
            cv::Vec3b(image.channel(u, v, 2), image.channel(u, v, 1), image.channel(u, v, 0));
        }
      }
      s.frames.push_back(bgr);
      s.depth.push_back(image.depth);
      s.names.push_back("frame" + std::to_string(100 + f).substr(1) + ".png");
    }
    return s;
  }();
  return s;
}

} // namespace vimlop::fixtures

#endif
