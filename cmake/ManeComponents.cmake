# Which of mane's libraries this build makes: MANE_COMPONENTS, any of
#
#   physics   hair, fur and cloth on the CPU         needs GLM
#   subdiv    Catmull-Clark limit surfaces          needs GLM, OpenSubdiv
#   render    the Vulkan renderer                   needs GLM, Vulkan, glslang, stb
#   scene     scene files, assets, the frame loop   needs the three above and the loaders' libraries
#
# A component brings in the components it builds on. Only the packages of the chosen components
# are looked for (cmake/ManeDependencies.cmake): -DMANE_COMPONENTS=physics needs nothing but
# CMake, a C++23 compiler and GLM. The `mane` program, the tests and the benchmarks use every
# component; with fewer they are left out.

set(_mane_known physics subdiv render scene)
foreach(component IN LISTS MANE_COMPONENTS)
  if(NOT component IN_LIST _mane_known)
    list(JOIN _mane_known ", " known_text)
    message(FATAL_ERROR "MANE_COMPONENTS: unknown component '${component}' (known: ${known_text})")
  endif()
endforeach()
if("scene" IN_LIST MANE_COMPONENTS)
  list(APPEND MANE_COMPONENTS physics subdiv render)
endif()
# The canonical order, without repeats: it is also the order written into the package files.
set(_mane_resolved "")
foreach(component IN LISTS _mane_known)
  if(component IN_LIST MANE_COMPONENTS)
    list(APPEND _mane_resolved ${component})
  endif()
endforeach()
if(NOT _mane_resolved)
  message(FATAL_ERROR "MANE_COMPONENTS is empty: name at least one of ${_mane_known}")
endif()
set(MANE_COMPONENTS ${_mane_resolved})
message(STATUS "mane components: ${MANE_COMPONENTS}")

if(NOT _mane_resolved STREQUAL "physics;subdiv;render;scene")
  foreach(part APP TESTS BENCH)
    if(MANE_BUILD_${part})
      message(STATUS "mane: MANE_BUILD_${part} needs every component; skipped")
      set(MANE_BUILD_${part} OFF)
    endif()
  endforeach()
endif()
