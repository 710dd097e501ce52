# Usage: cmake -DDIR=<folder> "-DFILES=a;b/c;..." [-DFILE=<json> "-DKEYS=..."] -P check-files.cmake
# Fails unless every file exists (and is not empty) in DIR; with FILE and KEYS,
# also checks that every key of the JSON file holds a number (check-json-numbers.cmake).
foreach(name IN LISTS FILES)
  if(NOT EXISTS "${DIR}/${name}")
    message(FATAL_ERROR "${DIR}: '${name}' is missing")
  endif()
  file(SIZE "${DIR}/${name}" size)
  if(size EQUAL 0)
    message(FATAL_ERROR "${DIR}: '${name}' is empty")
  endif()
  message(STATUS "${name}: ${size} bytes")
endforeach()
if(DEFINED FILE)
  include("${CMAKE_CURRENT_LIST_DIR}/check-json-numbers.cmake")
endif()
