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

add_library(mane_determinism INTERFACE)
target_compile_options(mane_determinism INTERFACE -ffp-contract=off -fno-math-errno)

# Simulation results are compared bit for bit across build types: keep contraction off in
# every target, not only the physics, so CPU references in tests agree with the library.
add_compile_options(-ffp-contract=off)

string(FIND "${CMAKE_CXX_FLAGS}" "fast-math" _mane_fast_math)
if(NOT _mane_fast_math EQUAL -1)
  message(FATAL_ERROR "mane must not be built with -ffast-math (determinism, see docs/design.md#determinism)")
endif()
