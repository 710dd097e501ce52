# Test helpers.
#
#   vimlop_add_gtest(<name> SOURCES <file>... LIBRARIES <lib>... [RENDERING] [FIXTURES <f>...])
#
# builds one GoogleTest executable into bin/ and registers each of its tests
# with CTest. RENDERING tests need an X display (VTK 9.1 here is built for X11):
# they run through CMake/run-with-display.sh, which starts `xvfb-run -a` (Mesa
# llvmpipe) when no display is set.

include(GoogleTest)

set(VIMLOP_TEST_OUTPUT_DIR "${CMAKE_BINARY_DIR}/Testing/Temporary")
file(MAKE_DIRECTORY "${VIMLOP_TEST_OUTPUT_DIR}")
set(VIMLOP_DISPLAY_LAUNCHER "${PROJECT_SOURCE_DIR}/CMake/run-with-display.sh")

function(vimlop_add_gtest name)
  cmake_parse_arguments(arg "RENDERING" "" "SOURCES;LIBRARIES;FIXTURES" ${ARGN})
  add_executable(${name} ${arg_SOURCES})
  target_link_libraries(${name} PRIVATE ${arg_LIBRARIES} GTest::gtest GTest::gtest_main
                                        VIMLOP::BuildSettings)
  target_compile_definitions(${name} PRIVATE
    VIMLOP_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/Testing/Data"
    VIMLOP_TEST_OUTPUT_DIR="${VIMLOP_TEST_OUTPUT_DIR}")
  set(labels "${name}")
  if(arg_RENDERING)
    list(APPEND labels rendering)
    # GoogleTest discovery and every test run go through this launcher.
    set_target_properties(${name} PROPERTIES CROSSCOMPILING_EMULATOR "${VIMLOP_DISPLAY_LAUNCHER}")
  endif()
  # PROPERTIES is a flat key-value list: a list value needs its ';' escaped.
  # (CMake 3.25's discovery script flattens it once more, so a list value
  # must come last: only its first item is kept.)
  string(REPLACE ";" "\\;" labels "${labels}")
  set(properties)
  if(arg_FIXTURES)
    # Tests that read what a CLI test (a fixture) wrote first require it.
    list(APPEND properties FIXTURES_REQUIRED "${arg_FIXTURES}")
  endif()
  # Discovery at test time keeps configuring fast and lists every TEST in ctest.
  gtest_discover_tests(${name}
    DISCOVERY_MODE PRE_TEST
    DISCOVERY_TIMEOUT 60
    PROPERTIES ${properties} LABELS "${labels}")
endfunction()

#   vimlop_add_cli_test(<name> COMMAND <args>... [PASS_REGEX <re>] [EXPECT_ERROR <re>]
#                       [JSON_KEYS <key>...] [JSON_VALUES <key=value>...] [RENDERING])
#
# runs the `vimlop` program. PASS_REGEX checks the output of a successful run;
# EXPECT_ERROR demands a non-zero exit code without a crash and an output that
# matches <re> (the one-line message the user sees). JSON_KEYS and
# JSON_VALUES check a --json run: a successful one whose standard output is
# one JSON object alone, with those keys and values (check-json-output.cmake).
function(vimlop_add_cli_test name)
  # PARSE_ARGV keeps a ';' inside one argument (a regular expression's);
  # parsing ${ARGN} would split it there and drop the rest unchecked.
  cmake_parse_arguments(PARSE_ARGV 1 arg "RENDERING" "PASS_REGEX;EXPECT_ERROR"
    "COMMAND;JSON_KEYS;JSON_VALUES")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "vimlop_add_cli_test(${name}): unexpected arguments ${arg_UNPARSED_ARGUMENTS}")
  endif()
  set(command $<TARGET_FILE:vimlop> ${arg_COMMAND})
  if(arg_RENDERING)
    set(command "${VIMLOP_DISPLAY_LAUNCHER}" ${command})
  endif()
  if(DEFINED arg_EXPECT_ERROR)
    # A ';' would split the expression into two arguments: any character instead.
    string(REPLACE ";" "." expect_error "${arg_EXPECT_ERROR}")
    set(command "${PROJECT_SOURCE_DIR}/CMake/expect-error.sh" "${expect_error}" ${command})
  endif()
  if(DEFINED arg_JSON_KEYS OR DEFINED arg_JSON_VALUES)
    # Commas between the items: a list would be split into arguments.
    string(REPLACE ";" "," keys "${arg_JSON_KEYS}")
    string(REPLACE ";" "," values "${arg_JSON_VALUES}")
    set(command ${CMAKE_COMMAND} "-DKEYS=${keys}" "-DVALUES=${values}"
      -P "${PROJECT_SOURCE_DIR}/CMake/check-json-output.cmake" -- ${command})
  endif()
  add_test(NAME ${name} COMMAND ${command} WORKING_DIRECTORY "${VIMLOP_TEST_OUTPUT_DIR}")
  if(arg_RENDERING)
    set_tests_properties(${name} PROPERTIES LABELS "cli;rendering")
  else()
    set_tests_properties(${name} PROPERTIES LABELS "cli")
  endif()
  if(arg_PASS_REGEX)
    # A ';' in the expression would make it a list of alternatives, any of
    # which passes the test: it stands for any character instead.
    string(REPLACE ";" "." pass_regex "${arg_PASS_REGEX}")
    set_tests_properties(${name} PROPERTIES PASS_REGULAR_EXPRESSION "${pass_regex}")
  endif()
endfunction()
