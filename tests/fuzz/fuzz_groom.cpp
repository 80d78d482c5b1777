// libFuzzer harness: bytes → a scratch .tfx and a scratch .hair → loadGroomFile on each (the
// same bytes through both parsers). Must return strands or an error, never crash, hang or
// leak; strands it returns must keep StrandSet's promises (≥ 2 finite points per strand, no
// zero-length segment).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "scenes/groom_loader.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

namespace {

void check(const mane::Result<mane::scenes::StrandSet>& groom) {
  if (!groom) return;
  if (groom->strands.empty()) std::abort();
  for (const std::vector<glm::vec3>& strand : groom->strands) {
    if (strand.size() < 2) std::abort();
    for (std::size_t i = 0; i < strand.size(); ++i) {
      const glm::vec3& p = strand[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
      if (i > 0 && p == strand[i - 1]) std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mane::fuzz::InputFile tfx("input.tfx");
  static const mane::fuzz::InputFile hair("input.hair");
  check(mane::scenes::loadGroomFile(tfx.write(data, size)));
  check(mane::scenes::loadGroomFile(hair.write(data, size)));
  return 0;
}
