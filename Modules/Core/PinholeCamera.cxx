#include <vimlop/Core/PinholeCamera.h>

#include <vimlop/Core/Error.h>

#include <cmath>
#include <sstream>

namespace vimlop
{

Eigen::Matrix3d PinholeCamera::matrix() const
{
  Eigen::Matrix3d k;
  k << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return k;
}

PinholeCamera PinholeCamera::fromMatrix(const Eigen::Matrix3d& k, int widthPx, int heightPx)
{
  PinholeCamera camera;
  camera.fx = k(0, 0);
  camera.fy = k(1, 1);
  camera.cx = k(0, 2);
  camera.cy = k(1, 2);
  camera.widthPx = widthPx;
  camera.heightPx = heightPx;
  if (k(0, 1) != 0.0 || k(1, 0) != 0.0 || k(2, 0) != 0.0 || k(2, 1) != 0.0 || k(2, 2) != 1.0)
  {
    throw Error("camera matrix must have the form [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
  }
  camera.validate();
  return camera;
}

bool PinholeCamera::hasDistortion() const
{
  if (this->lensModel == LensModel::Fisheye)
  {
    return this->distortion.size() > 0;
  }
  return this->distortion.size() > 0 && (this->distortion.array() != 0.0).any();
}

void PinholeCamera::validate() const
{
  std::ostringstream problem;
  if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy)) ||
    !distortion.allFinite())
  {
    problem << "intrinsics contain non-finite values";
  }
  else if (!(fx > 0.0) || !(fy > 0.0))
  {
    problem << "focal lengths must be positive (fx=" << fx << ", fy=" << fy << ")";
  }
  else if (widthPx <= 0 || heightPx <= 0)
  {
    problem << "image size must be positive (" << widthPx << "x" << heightPx << ")";
  }
  // Units: an endoscope's focal length is about 0.3 to 1.5 image widths in
  // pixels. One in mm or normalised (fx = 2.8, 0.9) is under a twentieth of
  // the width (a field of view over 168 deg); one for a ten times larger
  // image or in micrometres, over twenty widths (under 3 deg).
  else if (fx < 0.05 * widthPx || fy < 0.05 * heightPx)
  {
    problem << "focal lengths (fx=" << fx << ", fy=" << fy << ") are far too small for a "
            << widthPx << "x" << heightPx
            << " image (a field of view over 168 deg): intrinsics are in pixels, not mm or "
               "normalised";
  }
  else if (fx > 20.0 * widthPx || fy > 20.0 * heightPx)
  {
    problem << "focal lengths (fx=" << fx << ", fy=" << fy << ") are far too large for a "
            << widthPx << "x" << heightPx
            << " image (a field of view under 3 deg): are they for a larger image, or in other "
               "units than pixels?";
  }
  else if (cx < -widthPx || cx > 2.0 * widthPx || cy < -heightPx || cy > 2.0 * heightPx)
  {
    problem << "principal point (" << cx << ", " << cy << ") is far outside the " << widthPx << "x"
            << heightPx << " image";
  }
  else if (lensModel == LensModel::Fisheye && distortion.size() != 4)
  {
    problem << "the fisheye lens model needs exactly 4 distortion coefficients (k1, k2, k3, k4), "
               "not "
            << distortion.size();
  }
  else if (const Eigen::Index n = distortion.size(); lensModel == LensModel::RadialTangential &&
           n != 0 && n != 4 && n != 5 && n != 8 && n != 12 && n != 14)
  {
    // OpenCV's models, which undistort the frames, take no other count.
    problem << "the radial-tangential lens model needs 4, 5, 8, 12 or 14 distortion "
               "coefficients (OpenCV's k1, k2, p1, p2[, k3[, k4, k5, k6[, s1, s2, s3, s4[, tx, "
               "ty]]]]), not "
            << n;
  }
  if (!problem.str().empty())
  {
    throw Error(problem.str());
  }
}

PinholeCamera PinholeCamera::resampled(double factor) const
{
  PinholeCamera k = *this;
  k.fx = factor * this->fx;
  k.fy = factor * this->fy;
  k.cx = factor * (this->cx + 0.5) - 0.5;
  k.cy = factor * (this->cy + 0.5) - 0.5;
  k.widthPx = static_cast<int>(std::lround(factor * this->widthPx));
  k.heightPx = static_cast<int>(std::lround(factor * this->heightPx));
  return k;
}

PinholeCamera PinholeCamera::simulatedEndoscope()
{
  PinholeCamera k;
  k.fx = k.fy = 200.0;
  k.cx = 159.5;
  k.cy = 119.5;
  k.widthPx = 320;
  k.heightPx = 240;
  return k;
}

} // namespace vimlop
