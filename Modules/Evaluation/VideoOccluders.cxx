#include <vimlop/Evaluation/VideoArtifacts.h>

// The occluders of VideoArtifacts.h (fluid and blood on the lens), apart
// from the optical artifacts: their own geometry and sizing.

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace vimlop
{

std::vector<bool> occludedFrames(int frames, double fraction, std::uint64_t seed)
{
  std::vector<bool> occluded(static_cast<size_t>(std::max(frames, 0)), false);
  const long count = std::lround(std::clamp(fraction, 0.0, 1.0) * frames);
  std::vector<int> order(occluded.size());
  std::iota(order.begin(), order.end(), 0);
  // A Fisher-Yates shuffle written out: std::shuffle's order differs between
  // standard libraries, and the choice must not.
  std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ull + 101u);
  for (size_t i = order.size(); i > 1; --i)
  {
    std::swap(order[i - 1], order[rng() % i]);
  }
  for (long i = 0; i < count; ++i)
  {
    occluded[order[i]] = true;
  }
  return occluded;
}

std::vector<bool> wallContactFrames(
  int frames, double fraction, int stretchFrames, std::uint64_t seed)
{
  std::vector<bool> touching(static_cast<size_t>(std::max(frames, 0)), false);
  const long wanted = std::lround(std::clamp(fraction, 0.0, 1.0) * frames);
  if (wanted == 0 || frames < 2 || stretchFrames < 1)
  {
    return touching;
  }
  std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ull + 211u);
  long covered = 0;
  // Starts drawn until enough frames are covered; a start whose stretch
  // (with a frame either side) meets another is drawn again, a bounded
  // number of times, so that a crowded sequence ends with fewer.
  for (int attempt = 0; covered < wanted && attempt < 100 * frames; ++attempt)
  {
    const int start = 1 + static_cast<int>(rng() % static_cast<std::uint64_t>(frames - 1));
    const int end = std::min(frames, start + stretchFrames);
    const int before = std::max(0, start - 1);
    const int after = std::min(frames, end + 1);
    if (std::any_of(touching.begin() + before, touching.begin() + after, [](bool t) { return t; }))
    {
      continue;
    }
    std::fill(touching.begin() + start, touching.begin() + end, true);
    covered += end - start;
  }
  return touching;
}

void applyWallContact(cv::Mat& light)
{
  const double sigma = std::max(1.0, light.cols / 5.0);
  cv::Mat blurred;
  cv::GaussianBlur(light, blurred, cv::Size(), sigma, sigma, cv::BORDER_REFLECT);
  // Tissue passes red and absorbs green and blue (BGR order).
  const cv::Scalar mean = cv::mean(light);
  const double brightness = 1.5 * (mean[0] + mean[1] + mean[2]) / 3.0;
  std::vector<cv::Mat> channels;
  cv::split(blurred, channels);
  cv::Mat grey = (channels[0] + channels[1] + channels[2]) / 3.0;
  const double scale = brightness / std::max(1e-6, cv::mean(grey)[0]);
  channels[2] = grey * (scale * 1.0);
  channels[1] = grey * (scale * 0.4);
  channels[0] = grey * (scale * 0.2);
  cv::merge(channels, light);
}

namespace
{

struct Blob
{
  double cu, cv;             // centre, pixels
  double radius;             // relative to the scale
  double aspect;             // of the ellipse
  double cosAngle, sinAngle; // its orientation
  double amplitude[2];       // the outline's waves
  int waves[2];
  double phase[2];
};

double uniform(std::mt19937_64& rng, double low, double high)
{
  // From the raw 64 bits: std::uniform_real_distribution differs between libraries.
  return low + (high - low) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
}

/**
 * Each blob's edge at each pixel, apart from the scale (pixels per unit
 * radius), so that the bisection over the scale costs no trigonometry: the
 * edge parameter at scale s is `offset - distance / s`.
 */
struct BlobGeometry
{
  std::vector<float> offset;
  std::vector<float> distance;
};

std::vector<BlobGeometry> blobGeometry(const std::vector<Blob>& blobs, int w, int h)
{
  std::vector<BlobGeometry> geometry(blobs.size());
  for (size_t i = 0; i < blobs.size(); ++i)
  {
    const Blob& b = blobs[i];
    for (int v = 0; v < h; ++v)
    {
      for (int u = 0; u < w; ++u)
      {
        const double du = u - b.cu;
        const double dv = v - b.cv;
        const double x = b.cosAngle * du + b.sinAngle * dv;
        const double y = (-b.sinAngle * du + b.cosAngle * dv) / b.aspect;
        const double phi = std::atan2(y, x);
        const double outline = b.radius *
          (1.0 + b.amplitude[0] * std::sin(b.waves[0] * phi + b.phase[0]) +
            b.amplitude[1] * std::sin(b.waves[1] * phi + b.phase[1]));
        // A soft edge of 30 % of the radius, 0.5 on the outline: a drop's
        // rim is not sharp. t = (s outline - rho) / (0.3 s radius) + 0.5.
        const double edge = 0.3 * b.radius;
        geometry[i].offset.push_back(static_cast<float>(outline / edge + 0.5));
        geometry[i].distance.push_back(static_cast<float>(std::hypot(x, y) / edge));
      }
    }
  }
  return geometry;
}

/// The union of the blobs' coverage at this scale (pixels per unit radius).
cv::Mat blobCoverage(const std::vector<BlobGeometry>& geometry, int w, int h, double scale)
{
  cv::Mat coverage(h, w, CV_32F, cv::Scalar(0.0f));
  for (int v = 0; v < h; ++v)
  {
    for (int u = 0; u < w; ++u)
    {
      const size_t k = static_cast<size_t>(v) * w + u;
      double clear = 1.0;
      for (const BlobGeometry& g : geometry)
      {
        const double t = std::clamp(g.offset[k] - g.distance[k] / scale, 0.0, 1.0);
        clear *= 1.0 - t * t * (3.0 - 2.0 * t);
      }
      coverage.at<float>(v, u) = static_cast<float>(1.0 - clear);
    }
  }
  return coverage;
}

double coveredFraction(const cv::Mat& coverage)
{
  return static_cast<double>(cv::countNonZero(coverage >= 0.5f)) / coverage.total();
}

} // namespace

cv::Mat occluderCoverage(int widthPx, int heightPx, double areaFraction, std::uint64_t seed)
{
  std::mt19937_64 rng(seed * 0xbf58476d1ce4e5b9ull + 7u);
  std::vector<Blob> blobs(1 + rng() % 3);
  for (Blob& b : blobs)
  {
    b.cu = uniform(rng, 0.15, 0.85) * widthPx;
    b.cv = uniform(rng, 0.15, 0.85) * heightPx;
    b.radius = uniform(rng, 0.6, 1.0);
    b.aspect = uniform(rng, 0.6, 1.0);
    const double angle = uniform(rng, 0.0, M_PI);
    b.cosAngle = std::cos(angle);
    b.sinAngle = std::sin(angle);
    for (int k = 0; k < 2; ++k)
    {
      b.amplitude[k] = uniform(rng, 0.05, 0.15);
      b.waves[k] = 2 + static_cast<int>(rng() % 4);
      b.phase[k] = uniform(rng, 0.0, 2.0 * M_PI);
    }
  }
  // The covered area grows with the scale at every pixel: bisection finds
  // the scale of the requested area whatever the blobs' overlap and the
  // image's border cut off.
  const std::vector<BlobGeometry> geometry = blobGeometry(blobs, widthPx, heightPx);
  double low = 0.0;
  double high = 2.0 * std::hypot(widthPx, heightPx);
  for (int i = 0; i < 24; ++i)
  {
    const double mid = 0.5 * (low + high);
    (coveredFraction(blobCoverage(geometry, widthPx, heightPx, mid)) < areaFraction ? low : high) =
      mid;
  }
  return blobCoverage(geometry, widthPx, heightPx, high);
}

void applyOccluders(cv::Mat& light, const cv::Mat& coverage, double opacity)
{
  // Blood on the lens under the scope's light: dark red (BGR, grey levels).
  const cv::Vec3f colour(12.0f, 10.0f, 55.0f);
  for (int v = 0; v < light.rows; ++v)
  {
    for (int u = 0; u < light.cols; ++u)
    {
      const float c = static_cast<float>(opacity) * coverage.at<float>(v, u);
      cv::Vec3f& pixel = light.at<cv::Vec3f>(v, u);
      pixel = (1.0f - c) * pixel + c * colour;
    }
  }
}

} // namespace vimlop
