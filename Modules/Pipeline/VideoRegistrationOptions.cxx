#include <vimlop/Pipeline/VideoRegistrationOptions.h>

#include <vimlop/Core/Error.h>
#include <vimlop/Core/OptionRange.h>
#include <vimlop/Pipeline/VideoRegistrationOptionTable.h>

#include <filesystem>

namespace vimlop
{

RegistrationOptions VideoRegistrationOptions::registrationOptions(double initialScale) const
{
  RegistrationOptions o = this->registration;
  o.minScale = initialScale / this->scaleBoundFactor;
  o.maxScale = initialScale * this->scaleBoundFactor;
  return o;
}

void VideoRegistrationOptions::validate() const
{
#define VIMLOP_CHECK_VALUE(Name, Type, member, key, flag, min, max, help)                          \
  requireInRange("video registration options", key, this->member, min, max);
  VIMLOP_VIDEO_REGISTRATION_VALUES(VIMLOP_CHECK_VALUE)
#undef VIMLOP_CHECK_VALUE
  this->registration.validate();
  this->multiStart.validate();
  this->canonical.validate();
  if (this->fieldOfView.mode == FieldStopMode::File && this->fieldOfView.maskFile.empty())
  {
    throw Error("video registration options: the field stop's mask file is not given");
  }
  std::error_code ignored;
  if (this->fieldOfView.mode == FieldStopMode::File &&
    !std::filesystem::is_regular_file(this->fieldOfView.maskFile, ignored))
  {
    throw Error("video registration options: the field stop's mask file '" +
      this->fieldOfView.maskFile + "' does not exist");
  }
  if (this->fieldOfView.mode == FieldStopMode::Circle && !(this->fieldOfView.radiusPx > 0.0))
  {
    throw Error("video registration options: the field stop's circle needs a positive radius");
  }
}

} // namespace vimlop
