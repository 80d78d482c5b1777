# Shared by the packaging test scripts (cmake -P): run a step, stop the test with its output
# when it fails.

# run_step(<what> <command>...): runs the command, echoing it; a non-zero exit fails the test.
function(run_step what)
  list(JOIN ARGN " " shown)
  message(STATUS "${what}: ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (exit ${rc}):\n${out}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

# fresh_dir(<dir>): an empty folder, whatever an earlier run left there.
function(fresh_dir dir)
  file(REMOVE_RECURSE "${dir}")
  file(MAKE_DIRECTORY "${dir}")
endfunction()

# run_example(<program> <hash file>): runs examples/embed_physics as built, checks it printed a
# state hash and writes the hash to <hash file> for packaging.same_hash.
function(run_example program hash_file)
  file(REMOVE "${hash_file}")
  run_step("run" "${program}")
  message(STATUS "${step_output}")
  if(NOT step_output MATCHES "state hash: ([0-9a-f]+)")
    message(FATAL_ERROR "${program} printed no state hash:\n${step_output}")
  endif()
  file(WRITE "${hash_file}" "${CMAKE_MATCH_1}\n")
endfunction()

# The variables every script gets from tests/packaging/CMakeLists.txt.
foreach(var MANE_SOURCE_DIR MANE_BINARY_DIR WORK CXX GENERATOR LIBDIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "packaging test script run without -D${var}=...")
  endif()
endforeach()
set(PREFIX "${WORK}/prefix")
set(EXAMPLE_DIR "${MANE_SOURCE_DIR}/examples/embed_physics")
