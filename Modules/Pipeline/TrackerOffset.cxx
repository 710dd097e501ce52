#include <vimlop/Pipeline/TrackerOffset.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace vimlop
{

TrackerOffset::TrackerOffset(int memoryFrames, int priorFrames)
  : Memory(memoryFrames)
  , PriorFrames(priorFrames)
{
  if (memoryFrames < 1)
  {
    throw Error(
      "tracker offset: its memory must be at least 1 frame, not " + std::to_string(memoryFrames));
  }
  if (priorFrames < 0)
  {
    throw Error(
      "tracker offset: its prior frames must not be negative, not " + std::to_string(priorFrames));
  }
}

void TrackerOffset::learn(const CameraPose& videoCT, const TrackerPrior& prior)
{
  // 1/n over the first frames (their plain mean), then 1/memory: an
  // exponential mean that forgets what a slowly changing error left behind.
  ++this->Learned;
  const double weight = 1.0 / std::min(this->Learned, this->Memory);
  this->Shift += weight * ((videoCT.centre - prior.tipCT) - this->Shift);
  if (prior.rotationCT)
  {
    ++this->LearnedTurns;
    const double turnWeight = 1.0 / std::min(this->LearnedTurns, this->Memory);
    const Eigen::Matrix3d seen = videoCT.rotation * prior.rotationCT->transpose();
    // Along the geodesic from the mean so far towards this frame's turn.
    this->Turn = rotationTowards(this->Turn, seen, turnWeight);
  }
}

namespace
{

/// The share of a mean over `n` frames kept under a prior of `prior` frames of none.
double shrinkage(int n, int prior)
{
  return n == 0 ? 0.0 : static_cast<double>(n) / (n + prior);
}

} // namespace

TrackerPrior TrackerOffset::corrected(const TrackerPrior& prior) const
{
  TrackerPrior r = prior;
  r.tipCT += this->shiftMm();
  if (r.rotationCT)
  {
    r.rotationCT = nearestRotation(rotationFromVector(this->turnVector()) * *r.rotationCT);
  }
  return r;
}

bool TrackerOffset::positionChecked() const
{
  return this->Learned >= std::max(this->PriorFrames, 1);
}

bool TrackerOffset::rotationChecked() const
{
  return this->LearnedTurns >= std::max(this->PriorFrames, 1);
}

void TrackerOffset::clear()
{
  *this = TrackerOffset(this->Memory, this->PriorFrames);
}

Eigen::Vector3d TrackerOffset::shiftMm() const
{
  return shrinkage(this->Learned, this->PriorFrames) * this->Shift;
}

Eigen::Vector3d TrackerOffset::turnVector() const
{
  return shrinkage(this->LearnedTurns, this->PriorFrames) * rotationToVector(this->Turn);
}

double TrackerOffset::turnDeg() const
{
  return this->turnVector().norm() * 180.0 / M_PI;
}

} // namespace vimlop
