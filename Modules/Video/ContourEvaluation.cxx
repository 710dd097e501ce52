#include <vimlop/Video/ContourEvaluation.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/KdTree2D.h>
#include <vimlop/Core/Statistics.h>

#include <algorithm>
#include <cmath>

namespace vimlop
{

ContourEvaluation::ContourEvaluation()
  : ContourEvaluation(ContourEvaluationOptions())
{
}

ContourEvaluation::ContourEvaluation(const ContourEvaluationOptions& options)
  : Opts(options)
{
}

void ContourEvaluation::addFrame(const std::vector<ContourPoint>& detected,
  const std::vector<ModelContourPoint>& truth, const std::vector<double>& sampleDepthMm,
  const DepthMap& depth)
{
  if (sampleDepthMm.size() != truth.size())
  {
    throw Error("contour evaluation: one depth per true sample is needed");
  }
  const double tolerance2 = this->Opts.tolerancePx * this->Opts.tolerancePx;

  std::vector<Eigen::Vector2d> truthPixels;
  truthPixels.reserve(truth.size());
  for (const ModelContourPoint& t : truth)
  {
    truthPixels.push_back(t.pixel);
  }
  const KdTree2D truthTree(truthPixels);
  this->Detected += static_cast<int>(detected.size());
  for (const ContourPoint& d : detected)
  {
    const int nearest = truthTree.nearest(d.pixel);
    if (nearest < 0 || (truthPixels[nearest] - d.pixel).squaredNorm() > tolerance2)
    {
      continue;
    }
    ++this->Correct;
    const double cosine = std::clamp(d.normal.dot(truth[nearest].pixelNormal), -1.0, 1.0);
    this->NormalErrorsDeg.push_back(std::acos(cosine) * 180.0 / M_PI);
  }

  std::vector<Eigen::Vector2d> detectedPixels;
  for (const ContourPoint& d : detected)
  {
    detectedPixels.push_back(d.pixel);
  }
  const KdTree2D detectedTree(detectedPixels);
  const double b = this->Opts.borderPx;
  for (size_t i = 0; i < truth.size(); ++i)
  {
    const Eigen::Vector2d& p = truth[i].pixel;
    if (p.x() < b || p.y() < b || p.x() > depth.widthPx - 1 - b || p.y() > depth.heightPx - 1 - b)
    {
      continue;
    }
    const Eigen::Vector2d probe = p + this->Opts.depthProbePx * truth[i].pixelNormal;
    const int u = static_cast<int>(std::lround(probe.x()));
    const int v = static_cast<int>(std::lround(probe.y()));
    if (u < 0 || v < 0 || u >= depth.widthPx || v >= depth.heightPx)
    {
      continue;
    }
    const double far = depth.at(u, v);
    if (!(far >= (1.0 + this->Opts.minDepthGap) * sampleDepthMm[i]))
    {
      continue; // no visible step: not a contour any picture shows
    }
    ++this->Truth;
    const int nearest = detectedTree.nearest(p);
    if (nearest >= 0 && (detectedPixels[nearest] - p).squaredNorm() <= tolerance2)
    {
      ++this->Found;
    }
  }
}

double ContourEvaluation::precision() const
{
  return this->Detected > 0 ? static_cast<double>(this->Correct) / this->Detected : 0.0;
}

double ContourEvaluation::recall() const
{
  return this->Truth > 0 ? static_cast<double>(this->Found) / this->Truth : 0.0;
}

double ContourEvaluation::medianNormalErrorDeg() const
{
  return summarize(this->NormalErrorsDeg).median;
}

} // namespace vimlop
