#include "CTSlices.h"

#include <vimlop/Core/Error.h>
#include <vimlop/Core/FileError.h>
#include <vimlop/Imaging/CTVolume.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace vimlop
{

namespace
{

/// One slice: its name, the LPS directions of its columns and rows, and the
/// letters of its edges (left, right, top, bottom).
struct SlicePlane
{
  const char* name;
  Eigen::Vector3d columnAxis;
  Eigen::Vector3d rowAxis;
  std::array<const char*, 4> edges;
};

const std::array<SlicePlane, 3> planes = { {
  { "axial", Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), { "R", "L", "A", "P" } },
  { "coronal", Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitZ(), { "R", "L", "S", "I" } },
  { "sagittal", Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitZ(), { "A", "P", "S", "I" } },
} };

/// Trilinear HU at a physical point; NaN outside the volume.
double sample(const CTVolume& ct, const Eigen::Vector3d& pointMm)
{
  const std::array<double, 3> index = ct.physicalToIndex({ pointMm.x(), pointMm.y(), pointMm.z() });
  std::array<int, 3> low{};
  std::array<double, 3> t{};
  for (int d = 0; d < 3; ++d)
  {
    if (!(index[d] >= 0.0 && index[d] <= ct.dims[d] - 1))
    {
      return std::numeric_limits<double>::quiet_NaN();
    }
    low[d] = std::min(static_cast<int>(index[d]), std::max(ct.dims[d] - 2, 0));
    t[d] = index[d] - low[d];
  }
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    double weight = 1.0;
    std::array<int, 3> at{};
    for (int d = 0; d < 3; ++d)
    {
      const int up = (corner >> d) & 1;
      at[d] = std::min(low[d] + up, ct.dims[d] - 1);
      weight *= up ? t[d] : 1.0 - t[d];
    }
    if (weight > 0.0)
    {
      value += weight *
        ct.intensities[static_cast<size_t>(at[0]) +
          static_cast<size_t>(ct.dims[0]) * (at[1] + static_cast<size_t>(ct.dims[1]) * at[2])];
    }
  }
  return value;
}

} // namespace

void writeCTSlices(const CTVolume& ct, const std::vector<CameraPose>& camerasCT, size_t shown,
  const std::string& pngPath)
{
  if (ct.numberOfVoxels() == 0 || ct.intensities.size() != ct.numberOfVoxels())
  {
    throw Error("CT slices: the CT volume is empty");
  }
  if (shown >= camerasCT.size())
  {
    throw Error("CT slices: no camera to show");
  }
  const double pxPerMm = ctSlicePx / ctSliceFieldMm;
  const Eigen::Vector3d centre = camerasCT[shown].centre;
  const int gapPx = 4;
  cv::Mat figure(ctSlicePx, 3 * ctSlicePx + 2 * gapPx, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Scalar yellow(0, 215, 255);
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  for (size_t p = 0; p < planes.size(); ++p)
  {
    const SlicePlane& plane = planes[p];
    cv::Mat panel =
      figure(cv::Rect(static_cast<int>(p) * (ctSlicePx + gapPx), 0, ctSlicePx, ctSlicePx));
    // Pixel (u, v) is centred at (u + 0.5, v + 0.5); the scope at the panel's centre.
    const auto pointOf = [&](double u, double v)
    {
      return Eigen::Vector3d(centre + (u + 0.5 - 0.5 * ctSlicePx) / pxPerMm * plane.columnAxis +
        (v + 0.5 - 0.5 * ctSlicePx) / pxPerMm * plane.rowAxis);
    };
    const auto pixelOf = [&](const Eigen::Vector3d& x)
    {
      const Eigen::Vector3d d = x - centre;
      return cv::Point2d(0.5 * ctSlicePx + d.dot(plane.columnAxis) * pxPerMm - 0.5,
        0.5 * ctSlicePx + d.dot(plane.rowAxis) * pxPerMm - 0.5);
    };
    for (int v = 0; v < ctSlicePx; ++v)
    {
      auto* row = panel.ptr<cv::Vec3b>(v);
      for (int u = 0; u < ctSlicePx; ++u)
      {
        const double hu = sample(ct, pointOf(u, v));
        if (std::isnan(hu))
        {
          row[u] = cv::Vec3b(70, 45, 45); // beyond the scan: dark blue, not the black of air
          continue;
        }
        const auto grey = static_cast<unsigned char>(
          std::clamp((hu - (200.0 - 1000.0)) / 2000.0 * 255.0, 0.0, 255.0));
        row[u] = cv::Vec3b(grey, grey, grey);
      }
    }
    // The path, then the shown camera and where it looks.
    for (const CameraPose& camera : camerasCT)
    {
      cv::circle(panel, pixelOf(camera.centre), 1, yellow, cv::FILLED, cv::LINE_AA);
    }
    const cv::Point2d at = pixelOf(centre);
    cv::circle(panel, at, 5, yellow, 2, cv::LINE_AA);
    const cv::Point2d tip = pixelOf(centre + 15.0 * camerasCT[shown].viewDirection());
    if (cv::norm(tip - at) > 2.0)
    {
      cv::arrowedLine(panel, at, tip, yellow, 2, cv::LINE_AA, 0, 0.25);
    }
    const cv::Scalar white(255, 255, 255);
    cv::putText(panel, plane.name, cv::Point(6, 16), font, 0.45, white, 1, cv::LINE_AA);
    const int mid = ctSlicePx / 2;
    cv::putText(panel, plane.edges[0], cv::Point(4, mid + 5), font, 0.45, white, 1, cv::LINE_AA);
    cv::putText(
      panel, plane.edges[1], cv::Point(ctSlicePx - 14, mid + 5), font, 0.45, white, 1, cv::LINE_AA);
    cv::putText(panel, plane.edges[2], cv::Point(mid - 4, 16), font, 0.45, white, 1, cv::LINE_AA);
    cv::putText(
      panel, plane.edges[3], cv::Point(mid - 4, ctSlicePx - 6), font, 0.45, white, 1, cv::LINE_AA);
  }
  if (!cv::imwrite(pngPath, figure))
  {
    throwFileError(pngPath, "cannot write the picture");
  }
}

} // namespace vimlop
