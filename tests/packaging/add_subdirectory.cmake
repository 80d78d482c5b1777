# packaging.add_subdirectory: examples/embed_physics with mane's sources (MANE_SOURCE_DIR), which
# builds mane's physics alone inside the example's build. Every package the other components
# use is disabled, so the configure fails if a physics-only build looks for any of them. The
# mane inside that build is then installed (its own install script: the example adds it
# EXCLUDE_FROM_ALL, which leaves it out of the example's install) as the physics-only prefix
# packaging.unbuilt_component asks.
include("${CMAKE_CURRENT_LIST_DIR}/steps.cmake")

set(build "${WORK}/add_subdirectory")
fresh_dir("${build}")
set(disabled "")
foreach(package Vulkan glfw3 TinyGLTF tinyobjloader nlohmann_json OpenSSL CURL meshoptimizer CLI11 GTest benchmark
                pybind11 Python Python3)
  list(APPEND disabled "-DCMAKE_DISABLE_FIND_PACKAGE_${package}=ON")
endforeach()
# No build type (no optimisation, no debug information): the quickest build of the library. Its
# hash must still be the optimised builds' one (packaging.same_hash).
run_step("configure" "${CMAKE_COMMAND}" -S "${EXAMPLE_DIR}" -B "${build}" -G "${GENERATOR}" "-DCMAKE_CXX_COMPILER=${CXX}"
         -DCMAKE_BUILD_TYPE= "-DMANE_SOURCE_DIR=${MANE_SOURCE_DIR}" -DMANE_INSTALL=ON ${disabled})

# What the configure looked for lands in its cache: none of the other components' tools and
# libraries may be there.
file(STRINGS "${build}/CMakeCache.txt" looked_for
     REGEX "^(Vulkan_|GLSLANG_VALIDATOR|STB_|OPENSUBDIV_|glfw3_DIR|CURL_|OPENSSL_|TinyGLTF_DIR|CLI11_DIR|GTest_DIR|benchmark_DIR|pybind11_DIR)")
if(looked_for)
  message(FATAL_ERROR "a physics-only configure looked for other components' packages:\n${looked_for}")
endif()

run_step("build" "${CMAKE_COMMAND}" --build "${build}" --parallel 2)
run_example("${build}/embed_physics" "${WORK}/add_subdirectory.hash")

set(physics_only "${WORK}/physics-only-prefix")
fresh_dir("${physics_only}")
run_step("install" "${CMAKE_COMMAND}" --install "${build}/mane" --prefix "${physics_only}")
