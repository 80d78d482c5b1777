// libFuzzer harness: bytes → a scratch .obj → loadObj. Must return a mesh or an error,
// never crash, hang or leak; a mesh it returns must pass validate().

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "scenes/obj_loader.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mane::fuzz::InputFile obj("input.obj");
  auto mesh = mane::scenes::loadObj(obj.write(data, size));
  if (mesh && !mane::scenes::validate(*mesh).empty()) std::abort();
  return 0;
}
