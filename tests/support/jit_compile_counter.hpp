#pragma once
// Counts the shader functions lavapipe hands to LLVM's JIT (a compile, or a load from Mesa's
// shader cache), so a test can check that a steady frame compiles nothing.
//
// Why a test needs this: lavapipe (Mesa 22.3) folds uniform values that decide a branch or a
// loop's trip count into the shader and compiles it again every time its descriptors are
// bound, with no cache of those variants in memory. A shader written that way costs a compile
// per frame (docs/lavapipe.md#shader-recompiles-on-bind), hidden by Mesa's disk cache while it is
// warm.
//
// The count comes from interposing LLVMGetPointerToGlobal, the call that finishes each JIT
// compile: a binary using this must export the symbol (CMake: mane_count_jit_compiles).

#include <cstddef>

namespace mane::testing {

/// Shader functions JIT-compiled so far in this process; 0 where lavapipe never ran.
std::size_t jitCompiles();

}  // namespace mane::testing
