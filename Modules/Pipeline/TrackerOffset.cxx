#include <vimlop/Pipeline/TrackerOffset.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/Rotation.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace vimlop
{

TrackerOffset::TrackerOffset(int memoryFrames)
  : Memory(memoryFrames)
{
  if (memoryFrames < 1)
  {
    throw Error(
      "tracker offset: its memory must be at least 1 frame, not " + std::to_string(memoryFrames));
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
    this->Turn = nearestRotation(
      rotationFromVector(turnWeight * rotationToVector(seen * this->Turn.transpose())) *
      this->Turn);
  }
}

TrackerPrior TrackerOffset::corrected(const TrackerPrior& prior) const
{
  TrackerPrior r = prior;
  r.tipCT += this->Shift;
  if (r.rotationCT)
  {
    r.rotationCT = nearestRotation(this->Turn * *r.rotationCT);
  }
  return r;
}

void TrackerOffset::clear()
{
  *this = TrackerOffset(this->Memory);
}

double TrackerOffset::turnDeg() const
{
  return rotationToVector(this->Turn).norm() * 180.0 / M_PI;
}

} // namespace vimlop
