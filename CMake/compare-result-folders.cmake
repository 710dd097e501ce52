# Usage: cmake -DA=<folder> -DB=<folder> [-DFILES=a.vtp;b.vtt] [-DIGNORE=key;key]
#   -P compare-result-folders.cmake
# Fails unless the result.json of both result folders are identical once the
# timing fields are taken out (runtime_s, run_wall_s, and times_ms of every
# iteration), the thread count (parameters.threads, the one input that may
# differ) and the top-level keys in IGNORE (e.g. inputs and command_line of
# two runs given the same data in other files), and each of FILES is
# byte-identical in both. Guards determinism: the same
# inputs and seed must give the same result whatever the thread count.

function(read_stripped folder out)
  set(file "${folder}/result.json")
  if(NOT EXISTS "${file}")
    message(FATAL_ERROR "${file}: no such file")
  endif()
  file(READ "${file}" json)
  string(JSON json ERROR_VARIABLE error REMOVE "${json}" runtime_s)
  if(error)
    message(FATAL_ERROR "${file}: no runtime_s (${error})")
  endif()
  string(JSON json ERROR_VARIABLE error REMOVE "${json}" parameters threads)
  foreach(key IN ITEMS run_wall_s LISTS IGNORE)
    string(JSON json ERROR_VARIABLE error REMOVE "${json}" ${key})
  endforeach()
  string(JSON iterations LENGTH "${json}" history)
  if(iterations GREATER 0)
    math(EXPR last "${iterations} - 1")
    foreach(i RANGE ${last})
      string(JSON json REMOVE "${json}" history ${i} times_ms)
    endforeach()
  endif()
  set(${out} "${json}" PARENT_SCOPE)
endfunction()

read_stripped("${A}" a)
read_stripped("${B}" b)
if(NOT a STREQUAL b)
  # Name the first differing line, to say what changed (brackets would
  # stop CMake's list splitting, so they become parentheses here).
  foreach(v a b)
    string(REPLACE "[" "(" ${v} "${${v}}")
    string(REPLACE "]" ")" ${v} "${${v}}")
    string(REPLACE ";" "," ${v} "${${v}}")
    string(REPLACE "\n" ";" l${v} "${${v}}")
  endforeach()
  list(LENGTH la na)
  list(LENGTH lb nb)
  if(nb LESS na)
    set(na ${nb})
  endif()
  math(EXPR n "${na} - 1")
  foreach(i RANGE ${n})
    list(GET la ${i} x)
    list(GET lb ${i} y)
    if(NOT x STREQUAL y)
      message(FATAL_ERROR "result.json differs (timing aside) at line ${i}:\n  ${A}: ${x}\n  ${B}: ${y}")
    endif()
  endforeach()
  message(FATAL_ERROR "result.json differs (timing aside)")
endif()
foreach(name IN LISTS FILES)
  file(SHA256 "${A}/${name}" ha)
  file(SHA256 "${B}/${name}" hb)
  if(NOT ha STREQUAL hb)
    message(FATAL_ERROR "${name} differs between ${A} and ${B}")
  endif()
endforeach()
string(LENGTH "${a}" length)
message(STATUS "identical: result.json (${length} characters without timing) ${FILES}")
