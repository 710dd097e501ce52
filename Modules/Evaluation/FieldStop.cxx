#include <vimlop/Evaluation/FieldStop.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/TextFormat.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace vimlop
{

double FieldStopOptions::radiusFor(int widthPx, int heightPx) const
{
  if (this->radiusPx > 0.0)
  {
    return this->radiusPx;
  }
  return this->radiusFraction * 0.5 * std::hypot(widthPx, heightPx);
}

void FieldStopOptions::validate() const
{
  auto check = [](double value, const char* what)
  {
    if (!std::isfinite(value) || value < 0.0)
    {
      throw Error(std::string("the field stop's ") + what + " must be a finite number >= 0, not " +
        formatText("%g", value));
    }
  };
  check(this->radiusFraction, "radius fraction");
  check(this->radiusPx, "radius in pixels");
  check(this->edgeSoftnessPx, "edge softness");
  if (!this->centreOffsetPx.allFinite())
  {
    throw Error("the field stop's centre offset must be finite");
  }
  if (this->radiusFraction > 0.0 && this->radiusPx > 0.0)
  {
    throw Error("give the field stop's radius either as a fraction of the half-diagonal or in "
                "pixels, not both");
  }
  if (!(this->vignettingStrength >= 0.0 && this->vignettingStrength <= 1.0))
  {
    throw Error("the vignetting strength must lie in [0, 1], not " +
      formatText("%g", this->vignettingStrength));
  }
}

cv::Mat fieldStopGain(const FieldStopOptions& o, int widthPx, int heightPx)
{
  o.validate();
  cv::Mat gain(heightPx, widthPx, CV_32F, cv::Scalar(1.0f));
  const double radius = o.radiusFor(widthPx, heightPx);
  // Vignetting is measured to the circle's edge, or to the image corner when
  // there is no circle, so that its strength is the loss where the picture ends.
  const double reach = radius > 0.0 ? radius : 0.5 * std::hypot(widthPx, heightPx);
  const double cu = 0.5 * (widthPx - 1) + o.centreOffsetPx.x();
  const double cv = 0.5 * (heightPx - 1) + o.centreOffsetPx.y();
  for (int v = 0; v < heightPx; ++v)
  {
    for (int u = 0; u < widthPx; ++u)
    {
      const double r = std::hypot(u - cu, v - cv);
      double g = 1.0 - o.vignettingStrength * (r / reach) * (r / reach);
      if (radius > 0.0)
      {
        const double inside = o.edgeSoftnessPx > 0.0
          ? std::clamp((radius + 0.5 * o.edgeSoftnessPx - r) / o.edgeSoftnessPx, 0.0, 1.0)
          : (r <= radius ? 1.0 : 0.0);
        g *= inside;
      }
      gain.at<float>(v, u) = static_cast<float>(std::max(g, 0.0));
    }
  }
  return gain;
}

} // namespace vimlop
