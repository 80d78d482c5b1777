#include "tests/support/jit_compile_counter.hpp"

#include <dlfcn.h>
#include <link.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

std::atomic<std::size_t> compiles{0};

using GetPointerToGlobal = void* (*)(void*, void*);

// libLLVM's own LLVMGetPointerToGlobal. The driver loads libLLVM privately (RTLD_LOCAL), out of
// RTLD_NEXT's reach, so the library is found among the loaded objects by name.
GetPointerToGlobal llvmGetPointerToGlobal() {
  std::string path;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* found) {
        if (std::strstr(info->dlpi_name, "libLLVM") == nullptr) return 0;
        *static_cast<std::string*>(found) = info->dlpi_name;
        return 1;
      },
      &path);
  void* library = path.empty() ? nullptr : dlopen(path.c_str(), RTLD_LAZY | RTLD_NOLOAD);
  void* function = library == nullptr ? nullptr : dlsym(library, "LLVMGetPointerToGlobal");
  if (function == nullptr) {
    std::fprintf(stderr, "jit_compile_counter: no LLVMGetPointerToGlobal in a loaded libLLVM (%s)\n",
                 path.empty() ? "none loaded" : path.c_str());
    std::abort();
  }
  return reinterpret_cast<GetPointerToGlobal>(function);
}

}  // namespace

// Shadows libLLVM's function of this name for the whole process (the executable's exported
// symbols come first in the lookup) and forwards to it.
extern "C" void* LLVMGetPointerToGlobal(void* engine, void* global) {
  static const GetPointerToGlobal llvm = llvmGetPointerToGlobal();
  compiles.fetch_add(1, std::memory_order_relaxed);
  return llvm(engine, global);
}

namespace mane::testing {

std::size_t jitCompiles() {
  return compiles.load(std::memory_order_relaxed);
}

}  // namespace mane::testing
