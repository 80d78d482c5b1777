# packaging.unbuilt_component: find_package against the physics-only install finds physics, and
# fails with a message naming the cause for a component the install does not hold and for a
# name that is no component.
include("${CMAKE_CURRENT_LIST_DIR}/steps.cmake")

set(physics_only "${WORK}/physics-only-prefix")
set(project "${WORK}/unbuilt_component")

# find(<components> <result var> <output var>): configures a one-line project.
function(find components result_var output_var)
  set(dir "${project}/${components}")
  fresh_dir("${dir}/build")
  file(WRITE "${dir}/CMakeLists.txt" "cmake_minimum_required(VERSION 3.25)\nproject(find LANGUAGES CXX)\n"
                                     "find_package(mane CONFIG REQUIRED COMPONENTS ${components})\n")
  execute_process(COMMAND "${CMAKE_COMMAND}" -S "${dir}" -B "${dir}/build" -G "${GENERATOR}" "-DCMAKE_CXX_COMPILER=${CXX}"
                          "-DCMAKE_PREFIX_PATH=${physics_only}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  set(${result_var} ${rc} PARENT_SCOPE)
  set(${output_var} "${out}" PARENT_SCOPE)
endfunction()

find(physics rc out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "find_package(mane COMPONENTS physics) failed on the physics-only install:\n${out}")
endif()

find(render rc out)
string(REGEX REPLACE "[ \n]+" " " flat "${out}")
if(rc EQUAL 0 OR NOT flat MATCHES "built without its 'render' component")
  message(FATAL_ERROR "find_package(mane COMPONENTS render) on a physics-only install should fail naming the "
                      "missing component; exit ${rc}:\n${out}")
endif()
message(STATUS "render on a physics-only install:\n${out}")

find(physiks rc out)
string(REGEX REPLACE "[ \n]+" " " flat "${out}")
if(rc EQUAL 0 OR NOT flat MATCHES "no component 'physiks'")
  message(FATAL_ERROR "find_package(mane COMPONENTS physiks) should fail naming the unknown component; exit ${rc}:\n${out}")
endif()
