# packaging.pkg_config: examples/embed_physics/main.cpp compiled as one file with the flags of
# `pkg-config --cflags --libs mane-physics` from the fresh install, and run.
include("${CMAKE_CURRENT_LIST_DIR}/steps.cmake")

set(build "${WORK}/pkg_config")
fresh_dir("${build}")
set(ENV{PKG_CONFIG_PATH} "${PREFIX}/${LIBDIR}/pkgconfig")
run_step("pkg-config" "${PKG_CONFIG}" --cflags --libs mane-physics)
string(STRIP "${step_output}" flags)
message(STATUS "flags: ${flags}")
separate_arguments(flags UNIX_COMMAND "${flags}")
run_step("compile" "${CXX}" -O2 "${EXAMPLE_DIR}/main.cpp" ${flags} -o "${build}/embed_physics")
run_example("${build}/embed_physics" "${WORK}/pkg_config.hash")
