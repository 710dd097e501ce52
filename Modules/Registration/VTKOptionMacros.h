#ifndef vimlop_VTKOptionMacros_h
#define vimlop_VTKOptionMacros_h

/**
 * @file VTKOptionMacros.h
 * @brief VTK properties generated from the option tables
 * (RegistrationOptionTable.h, VideoRegistrationOptionTable.h), in the style of
 * vtkSetClampMacro and vtkBooleanMacro, for settings held in an options
 * struct rather than in ivars of their own. VTK's wrappers expand these
 * macros, so Python sees every generated method.
 */

/// Set<Name> (clamped into [min, max], Modified() when it changes), Get<Name>,
/// Get<Name>MinValue and Get<Name>MaxValue for the numeric setting at `field`.
#define vtkVIMLOPValueOptionMacro(field, Name, Type, min, max)                                     \
  virtual void Set##Name(Type value)                                                               \
  {                                                                                                \
    const Type clamped = value < static_cast<Type>(min)                                            \
      ? static_cast<Type>(min)                                                                     \
      : (value > static_cast<Type>(max) ? static_cast<Type>(max) : value);                         \
    if (field != clamped)                                                                          \
    {                                                                                              \
      field = clamped;                                                                             \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  virtual Type Get##Name##MinValue() const                                                         \
  {                                                                                                \
    return static_cast<Type>(min);                                                                 \
  }                                                                                                \
  virtual Type Get##Name##MaxValue() const                                                         \
  {                                                                                                \
    return static_cast<Type>(max);                                                                 \
  }                                                                                                \
  virtual Type Get##Name() const                                                                   \
  {                                                                                                \
    return field;                                                                                  \
  }

/// Set<Name>, Get<Name>, <Name>On and <Name>Off for the switch at `field`.
#define vtkVIMLOPSwitchOptionMacro(field, Name)                                                    \
  virtual void Set##Name(bool on)                                                                  \
  {                                                                                                \
    if (field != on)                                                                               \
    {                                                                                              \
      field = on;                                                                                  \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  virtual bool Get##Name() const                                                                   \
  {                                                                                                \
    return field;                                                                                  \
  }                                                                                                \
  virtual void Name##On()                                                                          \
  {                                                                                                \
    this->Set##Name(true);                                                                         \
  }                                                                                                \
  virtual void Name##Off()                                                                         \
  {                                                                                                \
    this->Set##Name(false);                                                                        \
  }

/// One PrintSelf line per row of an option table: "Name: value".
#define vtkVIMLOPPrintValueOption(Name, Type, member, key, flag, min, max, help)                   \
  os << indent << #Name ": " << this->Get##Name() << "\n";
#define vtkVIMLOPPrintSwitchOption(Name, member, key, flag, help)                                  \
  os << indent << #Name ": " << (this->Get##Name() ? "On" : "Off") << "\n";

#endif
