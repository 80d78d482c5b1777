# packaging.install: `cmake --install` of this build into a fresh prefix, and the layout other
# projects rely on: headers under include/mane/, no internal headers, the CMake package files
# and the pkg-config file.
include("${CMAKE_CURRENT_LIST_DIR}/steps.cmake")

fresh_dir("${PREFIX}")
run_step("install" "${CMAKE_COMMAND}" --install "${MANE_BINARY_DIR}" --prefix "${PREFIX}" --config "${CONFIG}")

set(expected
  include/mane/common/error.hpp
  include/mane/physics/hair.hpp
  include/mane/physics/groom_generator.hpp
  "${LIBDIR}/cmake/mane/maneConfig.cmake"
  "${LIBDIR}/cmake/mane/maneConfigVersion.cmake"
  "${LIBDIR}/cmake/mane/maneTargets.cmake"
  "${LIBDIR}/pkgconfig/mane-physics.pc")
foreach(path IN LISTS expected)
  if(NOT EXISTS "${PREFIX}/${path}")
    message(FATAL_ERROR "the install has no ${path}")
  endif()
endforeach()

# Internal headers stay in the source tree: detail/ folders, and the window, which only the
# program links.
file(GLOB_RECURSE installed LIST_DIRECTORIES true RELATIVE "${PREFIX}/include" "${PREFIX}/include/*")
set(internal ${installed})
list(FILTER internal INCLUDE REGEX "(^|/)(detail|examples)(/|$)|/window\\.hpp$")
if(internal)
  message(FATAL_ERROR "internal headers were installed: ${internal}")
endif()
list(FILTER installed INCLUDE REGEX "\\.hpp$")
list(LENGTH installed count)
message(STATUS "installed ${count} headers into ${PREFIX}/include")
