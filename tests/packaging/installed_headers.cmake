# packaging.installed_headers: every installed header of the given components compiles alone,
# included as <mane/...> through the installed targets (tests/packaging/header_check).
include("${CMAKE_CURRENT_LIST_DIR}/steps.cmake")

# COMPONENTS: comma-separated, passed on as it is (a ';' would split the argument). The render
# and scene headers take minutes (each parses Vulkan-Hpp), so they are checked only on request:
# MANE_CHECK_ALL_HEADERS=1 ctest -R packaging.installed_headers
if("$ENV{MANE_CHECK_ALL_HEADERS}" STREQUAL "1")
  set(COMPONENTS "physics,subdiv,render,scene")
endif()

set(build "${WORK}/installed_headers")
fresh_dir("${build}")
run_step("configure" "${CMAKE_COMMAND}" -S "${CMAKE_CURRENT_LIST_DIR}/header_check" -B "${build}" -G "${GENERATOR}"
         "-DCMAKE_CXX_COMPILER=${CXX}" "-DCMAKE_PREFIX_PATH=${PREFIX}" "-DMANE_CHECK_COMPONENTS=${COMPONENTS}")
message(STATUS "${step_output}")
run_step("build" "${CMAKE_COMMAND}" --build "${build}" --parallel 2)
