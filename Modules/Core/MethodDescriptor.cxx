#include <vimlop/Core/MethodDescriptor.h>

#include <vimlop/Core/Error.h>

#include <string>

namespace vimlop
{

MethodDescriptor describeMethod(RegistrationMethod method)
{
  MethodDescriptor d;
  switch (method)
  {
    case RegistrationMethod::VIMLOP:
      return d;
    case RegistrationMethod::IMLP:
      d.usesContours = false;
      return d;
    case RegistrationMethod::TrimmedICP:
      d.usesContours = false;
      d.pointMatching = PointMatching::ClosestPoint;
      d.chiSquareTest = false;
      d.trimming = TrimSchedule::Throughout;
      d.anatomicalConstraint = false;
      d.poseEstimation = PoseEstimation::ClosedFormSimilarity;
      return d;
  }
  throw Error("registration: unknown method " + std::to_string(static_cast<int>(method)));
}

bool usesAnatomicalConstraint(const RegistrationOptions& options)
{
  return options.anatomicalConstraint && describeMethod(options.method).anatomicalConstraint;
}

} // namespace vimlop
