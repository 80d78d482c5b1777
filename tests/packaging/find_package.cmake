# packaging.find_package: examples/embed_physics configured against the fresh install through
# find_package(mane CONFIG REQUIRED COMPONENTS physics), built and run.
include("${CMAKE_CURRENT_LIST_DIR}/steps.cmake")

set(build "${WORK}/find_package")
fresh_dir("${build}")
run_step("configure" "${CMAKE_COMMAND}" -S "${EXAMPLE_DIR}" -B "${build}" -G "${GENERATOR}"
         "-DCMAKE_CXX_COMPILER=${CXX}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${PREFIX}")
run_step("build" "${CMAKE_COMMAND}" --build "${build}")
run_example("${build}/embed_physics" "${WORK}/find_package.hash")
