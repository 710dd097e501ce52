#include <vimlop/Report/RegisteredVideo.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Rendering/ContourOverlay.h>
#include <vimlop/Rendering/PNGImageIO.h>
#include <vimlop/Rendering/SurfaceView.h>
#include <vimlop/Rendering/vtkVIMLOPSilhouetteRenderer.h>

#include <vtkCellArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <vimlop/Results/RegistrationVerdict.h>
#include <vimlop/Video/FrameBanner.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace vimlop
{

namespace
{

/// An RGB unsigned char VTK image (row 0 at the bottom) as OpenCV's BGR picture (top row first).
cv::Mat toBgrTopDown(vtkImageData* rgb)
{
  if (rgb->GetScalarType() != VTK_UNSIGNED_CHAR || rgb->GetNumberOfScalarComponents() != 3)
  {
    throw Error("registered video: a picture is not RGB unsigned char");
  }
  int dims[3];
  rgb->GetDimensions(dims);
  const int w = dims[0];
  const int h = dims[1];
  const auto* in = static_cast<const unsigned char*>(rgb->GetScalarPointer());
  cv::Mat bgr(h, w, CV_8UC3);
  for (int row = 0; row < h; ++row)
  {
    const unsigned char* src = in + static_cast<size_t>(h - 1 - row) * w * 3;
    unsigned char* dst = bgr.ptr<unsigned char>(row);
    for (int u = 0; u < w; ++u)
    {
      dst[3 * u + 0] = src[3 * u + 2];
      dst[3 * u + 1] = src[3 * u + 1];
      dst[3 * u + 2] = src[3 * u + 0];
    }
  }
  return bgr;
}

/// `picture` under a band in the verdict's colour (green registered, red
/// flagged, amber unchecked: the report's) holding its headline.
cv::Mat underVerdictBanner(const cv::Mat& picture, const RegistrationVerdict& verdict)
{
  const BannerColour colour = verdict.status == VerdictStatus::Registered ? BannerColour::Green
    : verdict.status == VerdictStatus::Flagged                            ? BannerColour::Red
                                                                          : BannerColour::Amber;
  return underBanner(picture, colour, verdict.headline());
}

} // namespace

std::vector<std::string> writeRegisteredVideo(const RegistrationRecord& record,
  const std::string& folder, double fps, const std::function<bool()>& keepGoing)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(fs::path(folder) / "registered", ec);
  if (ec)
  {
    throw Error("'" + folder + "/registered': cannot create the folder (" + ec.message() + ")");
  }
  // One window each for the contours and the views, kept for every frame.
  vtkNew<vtkVIMLOPSilhouetteRenderer> silhouettes;
  silhouettes->SetMesh(record.model);
  SurfaceView views(record.model);
  std::vector<std::string> written;
  cv::VideoWriter video;
  const std::string videoName = "registered-video.avi";
  const size_t count = std::min(record.data.frames.size(), record.result.frames.size());
  const RegistrationVerdict verdict = RegistrationVerdict::of(record);
  for (size_t j = 0; j < count && (!keepGoing || keepGoing()); ++j)
  {
    const VideoFrame& frame = record.data.frames[j];
    const CameraPose& pose = record.result.frames[j].cameraToCT;
    const int w = frame.intrinsics.widthPx;
    const int h = frame.intrinsics.heightPx;
    vtkSmartPointer<vtkImageData> picture;
    if (j < record.frameImages.size() && !record.frameImages[j].empty())
    {
      picture = readPNG((fs::path(folder) / record.frameImages[j]).string());
    }
    const auto overlay = composeContourOverlay(
      w, h, picture, silhouettes->RenderContours(frame.intrinsics, pose), frame.contour);
    const auto view = views.render(frame.intrinsics, pose);
    char name[64];
    std::snprintf(name, sizeof name, "registered/frame-%04d.png", frame.frameId);
    const std::string path = (fs::path(folder) / name).string();
    // The picture and the video's frame are one, with the verdict above.
    const cv::Mat side =
      underVerdictBanner(toBgrTopDown(placeSideBySide({ overlay, view }, 4)), verdict);
    if (!cv::imwrite(path, side))
    {
      throwFileError(path, "cannot write the picture");
    }
    written.push_back(name);

    if (!video.isOpened())
    {
      video.open((fs::path(folder) / videoName).string(),
        cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, side.size());
      if (!video.isOpened())
      {
        throwFileError((fs::path(folder) / videoName).string(), "cannot write the video");
      }
    }
    video.write(side);
  }
  if (video.isOpened())
  {
    video.release();
    written.push_back(videoName);
  }
  return written;
}

void writeCameraPath(const RegistrationResult& result, const std::string& path)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkIntArray> ids;
  ids->SetName("FrameId");
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell(static_cast<vtkIdType>(result.frames.size()));
  for (const FrameResult& f : result.frames)
  {
    lines->InsertCellPoint(points->InsertNextPoint(f.cameraToCT.centre.data()));
    ids->InsertNextValue(f.frameId);
  }
  vtkNew<vtkPolyData> path3d;
  path3d->SetPoints(points);
  path3d->SetLines(lines);
  path3d->GetPointData()->AddArray(ids);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(path3d);
  if (writer->Write() != 1)
  {
    throwFileError(path, "cannot write the camera path");
  }
}

} // namespace vimlop
