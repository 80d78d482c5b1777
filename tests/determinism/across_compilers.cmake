# determinism.across-compilers (cmake -P): every scene in scenes/ gives the same hashes when the
# simulation is built by a second compiler as when it is built by this build's compiler
# (docs/design.md#determinism). The second build (tests/determinism/across_compilers/) holds
# mane's libraries and the scene hash printer alone; it stays in WORK between runs, so a later
# run compiles only what changed.
#
# Variables: MANE_SOURCE_DIR; FIRST_NAME and FIRST_HASHES, this build's compiler (for messages)
# and its printer; SECOND_CXX, the second compiler (empty or *-NOTFOUND: the test is skipped), and
# SECOND_PACKAGE, the Debian package that brings it (for the skip message); GENERATOR,
# BUILD_TYPE, WORK, STEPS.

foreach(var MANE_SOURCE_DIR FIRST_NAME FIRST_HASHES GENERATOR WORK STEPS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "across_compilers.cmake run without -D${var}=...")
  endif()
endforeach()

# CTest's SKIP_REGULAR_EXPRESSION for this test (tests/determinism/CMakeLists.txt).
if(NOT SECOND_CXX OR NOT EXISTS "${SECOND_CXX}")
  message("determinism.across-compilers skipped: no second compiler (apt-get install ${SECOND_PACKAGE} and "
          "configure again, or name one with -DMANE_SECOND_CXX=...)")
  return()
endif()

if(NOT EXISTS "${FIRST_HASHES}")
  message(FATAL_ERROR "${FIRST_HASHES} is not built: build the target mane_scene_hashes first")
endif()

# run_step(<what> <command>...): runs the command; a non-zero exit fails the test with its output.
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " shown)
    message(FATAL_ERROR "${what} failed (exit ${rc}): ${shown}\n${out}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

get_filename_component(second_name "${SECOND_CXX}" NAME)
set(build "${WORK}/${second_name}")
string(TIMESTAMP started "%s")
# Configured every time (seconds, with the cache of the last run), so that a half-finished
# configure or a changed option never leaves a stale build.
run_step("configuring the ${second_name} build" "${CMAKE_COMMAND}" -S "${MANE_SOURCE_DIR}/tests/determinism/across_compilers"
         -B "${build}" -G "${GENERATOR}" "-DCMAKE_CXX_COMPILER=${SECOND_CXX}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
         "-DMANE_SOURCE_DIR=${MANE_SOURCE_DIR}")
run_step("building mane_scene_hashes with ${second_name}" "${CMAKE_COMMAND}" --build "${build}" --target mane_scene_hashes
         --parallel 2)
string(TIMESTAMP built "%s")
math(EXPR build_seconds "${built} - ${started}")
message(STATUS "${second_name} build: ${build_seconds} s")

file(GLOB scenes "${MANE_SOURCE_DIR}/scenes/*.json")
list(FILTER scenes EXCLUDE REGEX "/assets\\.json$")
list(SORT scenes)

# scene_hashes(<printer> <list>): the "SCENE WHAT HASH" lines the printer gives for every scene.
function(scene_hashes printer list)
  run_step("${printer}" "${printer}" --steps "${STEPS}" --threads 2 ${scenes})
  string(REGEX MATCHALL "[^\n]+" lines "${step_output}")
  list(FILTER lines INCLUDE REGEX "^[^ ]+ [^ ]+ [0-9a-f]+$")
  set(${list} "${lines}" PARENT_SCOPE)
endfunction()
scene_hashes("${FIRST_HASHES}" first_lines)
scene_hashes("${build}/mane_scene_hashes" second_lines)

list(LENGTH scenes scene_count)
list(LENGTH first_lines line_count)
list(LENGTH second_lines second_count)
if(line_count EQUAL 0 OR NOT line_count EQUAL second_count)
  message(FATAL_ERROR "the printers gave ${line_count} and ${second_count} hash lines for ${scene_count} scenes")
endif()
set(differences "")
math(EXPR last "${line_count} - 1")
foreach(i RANGE ${last})
  list(GET first_lines ${i} first)
  list(GET second_lines ${i} second)
  if(NOT first STREQUAL second)
    string(REPLACE " " ";" first "${first}")
    string(REPLACE " " ";" second "${second}")
    list(GET first 0 scene)
    list(GET first 1 what)
    list(GET first 2 first_hash)
    list(GET second 2 second_hash)
    string(APPEND differences "  ${scene} ${what}: ${FIRST_NAME} ${first_hash}, ${second_name} ${second_hash}\n")
  endif()
endforeach()
if(differences)
  message(FATAL_ERROR "scene hashes differ between ${FIRST_NAME} and ${second_name} (what each covers: "
                      "tests/determinism/scene_hashes.cpp):\n${differences}")
endif()
message(STATUS "${scene_count} scenes, ${line_count} hashes up to step ${STEPS}: ${FIRST_NAME} and ${second_name} agree")
