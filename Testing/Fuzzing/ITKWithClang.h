// Included first (-include) in the fuzz sources that use ITK. Debian's ITK
// 5.2 was configured with GCC and ships the compiler-detection header for
// GCC only, which stops clang with "Unsupported compiler". Clang implements
// every C++ feature that header tests for, so it is read here once, as GCC
// 12.2 would read it; its include guard then makes ITK's own include of it
// a no-op. Nothing else sees the changed macros.
#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Wbuiltin-macro-redefined"
#pragma push_macro("__clang__")
#pragma push_macro("__GNUC__")
#pragma push_macro("__GNUC_MINOR__")
#undef __clang__
#undef __GNUC__
#undef __GNUC_MINOR__
#define __GNUC__ 12
#define __GNUC_MINOR__ 2
#include <itk_compiler_detection.h>
#pragma pop_macro("__GNUC_MINOR__")
#pragma pop_macro("__GNUC__")
#pragma pop_macro("__clang__")
#pragma clang diagnostic pop
