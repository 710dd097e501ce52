// Built with -mavx2 (see CMakeLists.txt). It only holds a table of sizes and
// offsets, so that no code compiled for AVX2 runs (or is shared, through an
// inline function, with the rest of the test program) on a CPU without it.
#include "OptionLayout.h"

#define VIMLOP_LAYOUT_VALUE(name, value) value,

namespace
{
const std::size_t layoutValues[] = { VIMLOP_OPTION_LAYOUT(VIMLOP_LAYOUT_VALUE) };
}

const std::size_t* fixtures::optionLayoutWithAvx2(int& count)
{
  count = static_cast<int>(sizeof(layoutValues) / sizeof(layoutValues[0]));
  return layoutValues;
}
