#include <vimlop/Core/RegistrationData.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/NoiseModel.h>
#include <vimlop/Core/Rotation.h>

#include <cmath>
#include <string>

namespace vimlop
{

int RegistrationData::numberOfContourPoints() const
{
  int n = 0;
  for (const VideoFrame& frame : this->frames)
  {
    n += static_cast<int>(frame.contour.size());
  }
  return n;
}

void RegistrationData::validate() const
{
  if (this->points.empty())
  {
    throw Error("registration data: the point set is empty");
  }
  if (this->pointCovariances.size() != this->points.size())
  {
    throw Error("registration data: " + std::to_string(this->pointCovariances.size()) +
      " covariances for " + std::to_string(this->points.size()) + " points");
  }
  for (size_t i = 0; i < this->points.size(); ++i)
  {
    if (!this->points[i].allFinite())
    {
      throw Error("registration data: point " + std::to_string(i) + " is NaN or infinite");
    }
    const std::string problem = covarianceProblem(this->pointCovariances[i]);
    if (!problem.empty())
    {
      throw Error(
        "registration data: the covariance of point " + std::to_string(i) + " " + problem);
    }
  }
  for (size_t j = 0; j < this->frames.size(); ++j)
  {
    const VideoFrame& frame = this->frames[j];
    const std::string where = "registration data: frame " + std::to_string(frame.frameId);
    try
    {
      frame.intrinsics.validate();
    }
    catch (const Error& e)
    {
      throw Error(where + ": " + e.what());
    }
    if (!frame.cameraToSfm.centre.allFinite() || !isRotation(frame.cameraToSfm.rotation, 1e-6))
    {
      throw Error(where + ": the camera pose is not a finite rigid transform");
    }
    for (size_t i = 0; i < frame.contour.size(); ++i)
    {
      const ContourPoint& c = frame.contour[i];
      if (!c.pixel.allFinite() || !c.normal.allFinite())
      {
        throw Error(where + ": contour point " + std::to_string(i) + " is NaN or infinite");
      }
      if (std::abs(c.normal.norm() - 1.0) > 1e-3)
      {
        throw Error(
          where + ": the normal of contour point " + std::to_string(i) + " is not a unit vector");
      }
    }
  }
}

} // namespace vimlop
