#include <vimlop/Core/MultiStartRegistration.h>

#include <vimlop/Core/AnatomicalConstraint.h>
#include <vimlop/Core/Error.h>
#include <vimlop/Core/MethodDescriptor.h>
#include <vimlop/Core/TaskPool.h>
#include <vimlop/Core/TextFormat.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>

namespace vimlop
{

void MultiStartOptions::validate() const
{
  this->registration.validate();
  if (this->scaleFactors.empty())
  {
    throw Error("multi-start: at least one scale factor is needed");
  }
  for (double f : this->scaleFactors)
  {
    if (!(f > 0.0) || !std::isfinite(f))
    {
      throw Error("multi-start: scale factors must be positive, got " + std::to_string(f));
    }
  }
  if (this->screeningIterations < 0 || this->finalists < 1 || this->threads < 0 ||
    this->screeningStride < 1)
  {
    throw Error("multi-start: screening iterations and threads must be non-negative, and "
                "finalists and the screening stride at least 1");
  }
  if (!(this->failureContourErrorPx > 0.0))
  {
    throw Error("multi-start: the failure threshold must be positive");
  }
  if (!(this->failureResidualErrorMm > 0.0))
  {
    throw Error("multi-start: the failure threshold on the 3-D residual must be positive");
  }
  if (!(this->minMatchedFraction >= 0.0 && this->minMatchedFraction <= 1.0))
  {
    throw Error("multi-start: the least matched fraction must lie in [0, 1]");
  }
}

double matchedContourFraction(const RegistrationResult& result)
{
  long long matched = 0;
  long long points = 0;
  for (const FrameResult& f : result.frames)
  {
    matched += f.matched;
    points += f.contourPoints;
  }
  return points > 0 ? static_cast<double>(matched) / static_cast<double>(points) : 0.0;
}

std::string failureReason(const RegistrationResult& result, const MultiStartOptions& options)
{
  const double matched = matchedContourFraction(result);
  if (!(matched >= options.minMatchedFraction))
  {
    return formatText("only %.0f %% of the video contour points matched a model contour (at "
                      "least %.0f %% needed)",
      100.0 * matched, 100.0 * options.minMatchedFraction);
  }
  if (!(result.contourErrorPx <= options.failureContourErrorPx))
  {
    return formatText("the contour error %.2f px is above the threshold of %.2f px",
      result.contourErrorPx, options.failureContourErrorPx);
  }
  if (!(result.residualErrorMm <= options.failureResidualErrorMm))
  {
    return formatText("the 3-D residual %.2f mm is above the threshold of %.2f mm",
      result.residualErrorMm, options.failureResidualErrorMm);
  }
  return std::string();
}

bool isFlaggedAsFailure(const RegistrationResult& result, const MultiStartOptions& options)
{
  return !failureReason(result, options).empty();
}

void MultiStartResult::flagFailure(const MultiStartOptions& options)
{
  this->failureThresholdPx = options.failureContourErrorPx;
  this->failureResidualMm = options.failureResidualErrorMm;
  this->failureReason = vimlop::failureReason(this->best, options);
  this->failure = !this->failureReason.empty();
}

SimilarityTransform startFromCameraPose(
  const CameraPose& cameraToCT, const CameraPose& cameraToSfm, double scale)
{
  SimilarityTransform t;
  t.scale = scale;
  t.rotation = cameraToCT.rotation * cameraToSfm.rotation.transpose();
  t.translation = cameraToCT.centre - scale * t.rotation * cameraToSfm.centre;
  return t;
}

MultiStartResult registerMultiStart(const RegistrationModel& model, const RegistrationData& data,
  const std::vector<SimilarityTransform>& starts, const MultiStartOptions& options,
  const MultiStartProgress& progress)
{
  options.validate();
  data.validate();
  if (starts.empty())
  {
    throw Error("multi-start: no starting pose");
  }

  // The candidates, in a fixed order: start-major, then scale factor.
  MultiStartResult out;
  const RegistrationOptions& base = options.registration;
  for (size_t s = 0; s < starts.size(); ++s)
  {
    for (double factor : options.scaleFactors)
    {
      MultiStartCandidate c;
      c.start = static_cast<int>(s);
      c.scaleFactor = factor;
      c.initialSfmToCT = starts[s];
      c.initialSfmToCT.scale = std::clamp(starts[s].scale * factor, base.minScale, base.maxScale);
      if (!c.initialSfmToCT.isValid())
      {
        c.skipped = "not a valid similarity";
      }
      else if (int outside = -1; usesAnatomicalConstraint(base) &&
               !camerasInside(model, data.frames, c.initialSfmToCT, &outside))
      {
        c.skipped = "the camera of frame " + std::to_string(outside) + " starts outside the airway";
      }
      out.candidates.push_back(c);
    }
  }
  std::vector<int> runnable;
  for (size_t i = 0; i < out.candidates.size(); ++i)
  {
    if (out.candidates[i].skipped.empty())
    {
      runnable.push_back(static_cast<int>(i));
    }
  }
  if (runnable.empty())
  {
    throw Error("multi-start: none of the " + std::to_string(out.candidates.size()) +
      " candidates can start (" + out.candidates.front().skipped + ")");
  }

  // Each registration runs on one thread, the candidates in parallel (unless
  // the visibility backend, e.g. an OpenGL one, must stay on one thread).
  const int threads = model.visibility().isThreadSafe() ? options.threads : 1;
  TaskPool pool(threads);
  std::atomic<bool> cancelled{ false };
  std::mutex progressMutex;
  std::vector<RegistrationResult> results(out.candidates.size());
  // The screening's subsample: every stride-th frame (at least two) and point.
  RegistrationData screeningData;
  const size_t stride = static_cast<size_t>(options.screeningStride);
  const size_t frameStride = data.frames.size() >= 2 * stride ? stride : 1;
  for (size_t j = frameStride / 2; j < data.frames.size(); j += frameStride)
  {
    screeningData.frames.push_back(data.frames[j]);
  }
  for (size_t i = 0; i < data.points.size(); i += stride)
  {
    screeningData.points.push_back(data.points[i]);
    screeningData.pointCovariances.push_back(data.pointCovariances[i]);
  }
  if (screeningData.points.size() < 10 ||
    (describeMethod(base.method).usesContours && screeningData.numberOfContourPoints() == 0))
  {
    screeningData = data;
  }
  auto runPhase = [&](const char* phase, const RegistrationData& phaseData,
                    const std::vector<int>& which, int maxIterations)
  {
    int done = 0;
    if (progress && !progress(phase, 0, static_cast<int>(which.size())))
    {
      cancelled = true;
    }
    pool.run(static_cast<int>(which.size()),
      [&](int k)
      {
        if (cancelled)
        {
          return;
        }
        MultiStartCandidate& c = out.candidates[which[k]];
        RegistrationOptions o = base;
        o.threads = 1;
        o.maxIterations = maxIterations;
        results[which[k]] = registerVideo(model, phaseData, c.initialSfmToCT, o,
          [&](const IterationRecord&) { return !cancelled; });
        const RegistrationResult& r = results[which[k]];
        c.contourErrorPx = r.contourErrorPx;
        c.matchedFraction = matchedContourFraction(r);
        c.residualErrorMm = r.residualErrorMm;
        c.iterations += r.iterations;
        c.termination = r.termination;
        c.finalSfmToCT = r.sfmToCT;
        if (progress)
        {
          std::lock_guard<std::mutex> lock(progressMutex);
          if (!progress(phase, ++done, static_cast<int>(which.size())))
          {
            cancelled = true;
          }
        }
      });
    if (cancelled)
    {
      throw Error("multi-start: cancelled");
    }
  };

  // The least contour error first, after every candidate that matches too few
  // contour points; the candidate index breaks ties, so the order never
  // depends on which thread finished first.
  auto score = [&](int i)
  {
    const MultiStartCandidate& c = out.candidates[i];
    return c.matchedFraction >= options.minMatchedFraction
      ? c.contourErrorPx
      : std::numeric_limits<double>::infinity();
  };
  auto byContourError = [&](int a, int b)
  {
    const double ea = score(a);
    const double eb = score(b);
    return ea != eb ? ea < eb : a < b;
  };
  std::vector<int> finalists = runnable;
  if (options.screeningIterations > 0 && options.screeningIterations < base.maxIterations)
  {
    // Screening: each start once, at the scale factor closest to 1; the
    // starts whose screening ends with the least contour error go on, at
    // every scale factor.
    const auto nearestToOne =
      std::min_element(options.scaleFactors.begin(), options.scaleFactors.end(),
        [](double a, double b) { return std::abs(std::log(a)) < std::abs(std::log(b)); });
    const double screeningFactor = *nearestToOne;
    std::vector<int> screened;
    for (int i : runnable)
    {
      if (out.candidates[i].scaleFactor == screeningFactor)
      {
        screened.push_back(i);
      }
    }
    if (static_cast<int>(screened.size()) > options.finalists)
    {
      runPhase("screening", screeningData, screened, options.screeningIterations);
      for (int i : screened)
      {
        out.candidates[i].screeningContourErrorPx = out.candidates[i].contourErrorPx;
      }
      std::sort(screened.begin(), screened.end(), byContourError);
      screened.resize(options.finalists);
      std::vector<char> startGoesOn(starts.size(), 0);
      for (int i : screened)
      {
        startGoesOn[out.candidates[i].start] = 1;
      }
      finalists.clear();
      for (int i : runnable)
      {
        if (startGoesOn[out.candidates[i].start])
        {
          finalists.push_back(i);
        }
      }
    }
  }
  for (int i : finalists)
  {
    out.candidates[i].finalist = true;
  }
  runPhase("final", data, finalists, base.maxIterations);

  out.bestCandidate = *std::min_element(finalists.begin(), finalists.end(), byContourError);
  out.best = std::move(results[out.bestCandidate]);
  out.flagFailure(options);
  return out;
}

} // namespace vimlop
