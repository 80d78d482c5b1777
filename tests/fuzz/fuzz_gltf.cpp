// libFuzzer harness: bytes → a scratch file → loadGltf (binary .glb when the bytes start
// with "glTF", JSON otherwise; the loader picks by content, not by name). Must return a
// mesh or an error, never crash, hang or leak; a mesh it returns must pass validate().

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "scenes/gltf_loader.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Both names: .glb for binary containers, .gltf for JSON (buffers resolve beside it).
  static const mane::fuzz::InputFile glb("input.glb");
  static const mane::fuzz::InputFile gltf("input.gltf");
  const bool binary = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  auto mesh = mane::scenes::loadGltf((binary ? glb : gltf).write(data, size));
  if (mesh && !mane::scenes::validate(*mesh).empty()) std::abort();
  return 0;
}
