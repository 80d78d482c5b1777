# Warning and determinism flags shared by every mane target.
#
# mane_warnings:     -Wall -Wextra -Wpedantic, for our own code.
# mane_determinism:  -ffp-contract=off so a*b+c is never fused into an FMA whose rounding
#                    differs from the separate operations; no -ffast-math anywhere.
#                    -fno-math-errno lets std::sqrt vectorise without changing its result.

add_library(mane_warnings INTERFACE)
# Designated initialisers leave the other members value-initialised on purpose (Vulkan
# structs, settings structs); g++ 12 still warns about each of them.
target_compile_options(mane_warnings INTERFACE -Wall -Wextra -Wpedantic -Wno-missing-field-initializers)
# clang with libstdc++ 12: std::stable_sort calls std::get_temporary_buffer, which C++17
# deprecates, and clang reports that inside the library's own header at each of our calls
# (libstdc++ 13 silences it there). The g++ build still reports deprecations in our code.
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  include(CheckCXXSourceCompiles)
  check_cxx_source_compiles([[
#include <cstddef>
#if !defined(_GLIBCXX_RELEASE) || _GLIBCXX_RELEASE >= 13
#error not libstdc++ before 13
#endif
int main() {}
]] MANE_LIBSTDCXX_DEPRECATES_INSIDE_STABLE_SORT)
  if(MANE_LIBSTDCXX_DEPRECATES_INSIDE_STABLE_SORT)
    target_compile_options(mane_warnings INTERFACE -Wno-deprecated-declarations)
  endif()
endif()

add_library(mane_determinism INTERFACE)
target_compile_options(mane_determinism INTERFACE -ffp-contract=off -fno-math-errno)

# Simulation results are compared bit for bit across build types: keep contraction off in
# every target, not only the physics, so CPU references in tests agree with the library.
add_compile_options(-ffp-contract=off)

# Sanitizers for every target, ours and the test binaries alike (the asan and tsan presets in
# CMakePresets.json): what -fsanitize= takes, e.g. "address,undefined" or "thread". A finding
# stops the program, so the test that ran into it fails instead of printing and passing.
set(MANE_SANITIZE "" CACHE STRING "Sanitizers for every target, as -fsanitize= takes them (empty: none)")
if(MANE_SANITIZE)
  add_compile_options(-fsanitize=${MANE_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${MANE_SANITIZE})
endif()

string(FIND "${CMAKE_CXX_FLAGS}" "fast-math" _mane_fast_math)
if(NOT _mane_fast_math EQUAL -1)
  message(FATAL_ERROR "mane must not be built with -ffast-math (determinism, see docs/design.md#determinism)")
endif()
