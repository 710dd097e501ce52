# Compiler settings that apply to VIMLOP's own targets only (never to the
# dependencies' headers, which are included as SYSTEM by their imported targets).

find_program(VIMLOP_CCACHE ccache)
if(VIMLOP_CCACHE)
  set(CMAKE_C_COMPILER_LAUNCHER "${VIMLOP_CCACHE}")
  set(CMAKE_CXX_COMPILER_LAUNCHER "${VIMLOP_CCACHE}")
endif()

# Every VIMLOP target links this interface target privately: C++17, warnings
# and (optionally) sanitizers, without imposing them on code that consumes us.
add_library(VIMLOPBuildSettings INTERFACE)
add_library(VIMLOP::BuildSettings ALIAS VIMLOPBuildSettings)
set_target_properties(VIMLOPBuildSettings PROPERTIES EXPORT_NAME BuildSettings)
target_compile_features(VIMLOPBuildSettings INTERFACE cxx_std_17)
target_compile_options(VIMLOPBuildSettings INTERFACE
  $<$<COMPILE_LANG_AND_ID:CXX,GNU,Clang>:-Wall -Wextra -Wpedantic>)

if(VIMLOP_ENABLE_SANITIZERS AND VIMLOP_ENABLE_TSAN)
  message(FATAL_ERROR "VIMLOP_ENABLE_SANITIZERS and VIMLOP_ENABLE_TSAN exclude each other")
endif()

if(VIMLOP_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "VIMLOP_BUILD_FUZZERS needs clang (libFuzzer): configure with CXX=clang++")
  endif()
  # Our code gets coverage instrumentation and sanitizers; the fuzz
  # executables add the libFuzzer driver (Testing/Fuzzing).
  set(_vimlop_fuzz -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer)
  target_compile_options(VIMLOPBuildSettings INTERFACE ${_vimlop_fuzz})
  target_link_options(VIMLOPBuildSettings INTERFACE -fsanitize=address,undefined)
endif()

if(VIMLOP_ENABLE_TSAN)
  set(_vimlop_tsan -fsanitize=thread -fno-omit-frame-pointer)
  target_compile_options(VIMLOPBuildSettings INTERFACE ${_vimlop_tsan})
  target_link_options(VIMLOPBuildSettings INTERFACE ${_vimlop_tsan})
endif()

if(VIMLOP_ENABLE_SANITIZERS)
  set(_vimlop_sanitizers -fsanitize=address,undefined -fno-omit-frame-pointer
                         -fno-sanitize-recover=undefined)
  target_compile_options(VIMLOPBuildSettings INTERFACE ${_vimlop_sanitizers})
  target_link_options(VIMLOPBuildSettings INTERFACE ${_vimlop_sanitizers})
endif()

set(CMAKE_CXX_EXTENSIONS OFF)

# Only linked privately by our shared libraries, but exported with them.
install(TARGETS VIMLOPBuildSettings EXPORT VIMLOPTargets)
