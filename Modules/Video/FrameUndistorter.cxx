#include <vimlop/Video/FrameUndistorter.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace vimlop
{

FrameUndistorter::FrameUndistorter(const PinholeCamera& camera)
  : Camera(camera)
  , Distorted(camera.hasDistortion())
  , Fisheye(camera.hasDistortion() && camera.lensModel == LensModel::Fisheye)
{
  if (!this->Distorted)
  {
    return;
  }
  this->Matrix =
    (cv::Mat_<double>(3, 3) << camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0);
  this->Coefficients = cv::Mat(1, static_cast<int>(camera.distortion.size()), CV_64F);
  for (int i = 0; i < this->Coefficients.cols; ++i)
  {
    this->Coefficients.at<double>(i) = camera.distortion[i];
  }
  if (this->Fisheye)
  {
    // The undistorted frames keep K (as cv::undistort does for the other
    // model), so that the pinhole intrinsics downstream are the file's.
    cv::fisheye::initUndistortRectifyMap(this->Matrix, this->Coefficients, cv::Matx33d::eye(),
      this->Matrix, cv::Size(camera.widthPx, camera.heightPx), CV_32FC1, this->MapU, this->MapV);
  }
}

PinholeCamera FrameUndistorter::pinhole() const
{
  PinholeCamera k = this->Camera;
  k.removeDistortion();
  return k;
}

cv::Mat FrameUndistorter::undistort(const cv::Mat& frame) const
{
  if (frame.cols != this->Camera.widthPx || frame.rows != this->Camera.heightPx)
  {
    throw Error(formatText("undistortion: a frame of %d x %d pixels for a camera of %d x %d",
      frame.cols, frame.rows, this->Camera.widthPx, this->Camera.heightPx));
  }
  if (!this->Distorted)
  {
    return frame;
  }
  cv::Mat undistorted;
  if (this->Fisheye)
  {
    cv::remap(frame, undistorted, this->MapU, this->MapV, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
      cv::Scalar::all(0));
  }
  else
  {
    cv::undistort(frame, undistorted, this->Matrix, this->Coefficients);
  }
  return undistorted;
}

} // namespace vimlop
