# packaging.same_hash: the example's state hash is the same however it was built: optimised
# against the install (find_package), with plain g++ flags (pkg-config), and unoptimised from
# the sources (add_subdirectory).
include("${CMAKE_CURRENT_LIST_DIR}/steps.cmake")

string(REPLACE "," ";" builds "${BUILDS}")
set(first "")
foreach(build IN LISTS builds)
  file(STRINGS "${WORK}/${build}.hash" hash)
  message(STATUS "${build}: ${hash}")
  if(NOT first)
    set(first "${hash}")
  elseif(NOT hash STREQUAL first)
    message(FATAL_ERROR "the ${build} build's state hash ${hash} differs from ${first}")
  endif()
endforeach()
