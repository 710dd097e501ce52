#include <vimlop/Core/Error.h>
#include <vimlop/Core/RegistrationOptionTable.h>
#include <vimlop/Results/RecordJson.h>

#include <gtest/gtest.h>

#include <limits>

namespace vimlop::recordjson
{
namespace
{

TEST(RecordJson, EveryRowOfTheOptionTableSurvivesARoundTrip)
{
  // Every setting moved away from its default, to a value inside its range.
  RegistrationOptions o;
  int rows = 0;
#define VIMLOP_MOVE_VALUE(Name, Type, member, key, flag, min, max, help)                           \
  o.member = o.member == static_cast<Type>(max) ? static_cast<Type>(min) : static_cast<Type>(max); \
  ++rows;
#define VIMLOP_MOVE_SWITCH(Name, member, key, flag, help)                                          \
  o.member = !o.member;                                                                            \
  ++rows;
  VIMLOP_REGISTRATION_VALUES(VIMLOP_MOVE_VALUE)
  VIMLOP_REGISTRATION_SWITCHES(VIMLOP_MOVE_SWITCH)
#undef VIMLOP_MOVE_VALUE
#undef VIMLOP_MOVE_SWITCH
  EXPECT_NO_THROW(o.validate());

  const json j = optionsJson(o);
  // The table's rows, the method, Σ2d and the two scale bounds.
  EXPECT_EQ(static_cast<int>(j.size()), rows + 4);
  const RegistrationOptions back = optionsFrom(j);
#define VIMLOP_EXPECT_VALUE(Name, Type, member, key, flag, min, max, help)                         \
  EXPECT_EQ(back.member, o.member) << key;
#define VIMLOP_EXPECT_SWITCH(Name, member, key, flag, help) EXPECT_EQ(back.member, o.member) << key;
  VIMLOP_REGISTRATION_VALUES(VIMLOP_EXPECT_VALUE)
  VIMLOP_REGISTRATION_SWITCHES(VIMLOP_EXPECT_SWITCH)
#undef VIMLOP_EXPECT_VALUE
#undef VIMLOP_EXPECT_SWITCH
}

TEST(RecordJson, AnUnboundedScaleIsWrittenAsNullAndReadBackAsInfinity)
{
  const json j = optionsJson(RegistrationOptions());
  EXPECT_TRUE(j.at("max_scale").is_null());
  EXPECT_EQ(optionsFrom(j).maxScale, std::numeric_limits<double>::infinity());
}

TEST(RecordJson, AFractionalIterationCountIsAnErrorNamingItsKey)
{
  json j = optionsJson(RegistrationOptions());
  j["max_iterations"] = 2.5;
  try
  {
    optionsFrom(j);
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "\"max_iterations\" is not a whole number in range");
  }
}

TEST(RecordJson, AValueOutsideItsTableRangeIsRejectedByValidate)
{
  json j = optionsJson(RegistrationOptions());
  j["trim_fraction"] = 0.95;
  try
  {
    optionsFrom(j).validate();
    FAIL() << "expected an error";
  }
  catch (const Error& e)
  {
    EXPECT_STREQ(e.what(), "registration options: trim_fraction must lie in [0, 0.9], got 0.95");
  }
}

} // namespace
} // namespace vimlop::recordjson
