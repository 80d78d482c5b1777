// libFuzzer harness: bytes → a scratch .tfx and a scratch .hair → loadGroomFile on each (the
// same bytes through both parsers), repairing and strict. Must return strands or an error, never
// crash, hang or leak; strands it returns must keep StrandSet's promises (≥ 2 finite points per
// strand, no zero-length segment, attribute arrays aligned with the strands), and a strict load
// must succeed only where the repairing one found nothing to repair. The looks its attributes
// give (scenes/groom_looks.hpp) must be ones the renderer accepts, whatever the file holds.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>

#include "scenes/groom_loader.hpp"
#include "scenes/groom_looks.hpp"
#include "tests/fuzz/fuzz_input_file.hpp"

namespace {

template <class PerPoint>
void checkAligned(const std::vector<std::vector<PerPoint>>& perPoint, const mane::scenes::StrandSet& groom) {
  if (perPoint.empty()) return;
  if (perPoint.size() != groom.strands.size()) std::abort();
  for (std::size_t s = 0; s < perPoint.size(); ++s)
    if (perPoint[s].size() != groom.strands[s].size()) std::abort();
}

void check(const mane::Result<mane::scenes::StrandSet>& groom) {
  if (!groom) return;
  if (groom->strands.empty()) std::abort();
  if (groom->strands.size() + groom->repairs.droppedCount() != groom->repairs.strandsRead) std::abort();
  checkAligned(groom->thickness, *groom);
  checkAligned(groom->transparency, *groom);
  checkAligned(groom->colours, *groom);
  if (!groom->strandThickness.empty() && groom->strandThickness.size() != groom->strands.size()) std::abort();
  if (!groom->strandUvs.empty() && groom->strandUvs.size() != groom->strands.size()) std::abort();
  for (const std::vector<glm::vec3>& strand : groom->strands) {
    if (strand.size() < 2) std::abort();
    for (std::size_t i = 0; i < strand.size(); ++i) {
      const glm::vec3& p = strand[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
      if (i > 0 && p == strand[i - 1]) std::abort();
    }
  }
  // As a groom of its own, and at an odd scale that can push widths out of range.
  for (const float metresPerUnit : {0.01f, 3e38f}) {
    mane::scenes::GuideLooks looks;
    mane::scenes::appendFileLooks(*groom, mane::scenes::GroomRendering{}, metresPerUnit, looks);
    if (looks.guides.size() != groom->strands.size()) std::abort();
    // The ranges render::validateStrandLooks checks (its source needs a Vulkan device's types).
    const auto unit = [](float value) { return std::isfinite(value) && value >= 0.0f && value <= 1.0f; };
    for (const mane::render::HairStrandLook& look : looks.guides) {
      if (!(std::isfinite(look.widthScale) && look.widthScale > 0.0f)) std::abort();
      if (!unit(look.tipWidthScale) || !unit(look.opacityScale)) std::abort();
      if (!unit(look.colour.r) || !unit(look.colour.g) || !unit(look.colour.b)) std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mane::fuzz::InputFile tfx("input.tfx");
  static const mane::fuzz::InputFile hair("input.hair");
  for (const auto* input : {&tfx, &hair}) {
    const std::filesystem::path file = input->write(data, size);
    const auto repaired = mane::scenes::loadGroomFile(file);
    const auto strict = mane::scenes::loadGroomFile(file, {.strict = true});
    check(repaired);
    check(strict);
    if (strict && !(repaired && repaired->repairs.clean())) std::abort();
  }
  return 0;
}
