# The header layout every module follows: a header of module M is included
# as <vimlop/M/Header.h>, in the build tree as in an installed tree. The
# build tree gets it from a link include/vimlop/M to the module's folder, so
# that edits need no copy step; an install puts the public headers in
# include/vimlop/M.
set(VIMLOP_BUILD_INCLUDE_DIR "${CMAKE_BINARY_DIR}/include")

# The link include/vimlop/<module> -> the calling folder.
function(vimlop_link_module_headers module)
  set(link "${VIMLOP_BUILD_INCLUDE_DIR}/vimlop/${module}")
  if(NOT IS_SYMLINK "${link}")
    file(MAKE_DIRECTORY "${VIMLOP_BUILD_INCLUDE_DIR}/vimlop")
    file(CREATE_LINK "${CMAKE_CURRENT_SOURCE_DIR}" "${link}" SYMBOLIC)
  endif()
endfunction()

# Include directories of a plain (non-VTK) module target.
function(vimlop_module_include_directories target module)
  vimlop_link_module_headers(${module})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${VIMLOP_BUILD_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
endfunction()

# Installs a plain module target into the VIMLOPTargets export set and its
# public headers into include/vimlop/<module>.
function(vimlop_install_module target module)
  install(TARGETS ${target} EXPORT VIMLOPTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(FILES ${ARGN} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vimlop/${module})
endfunction()
