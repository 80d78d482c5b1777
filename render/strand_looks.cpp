#include "render/strand_looks.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace mane::render {
namespace {

bool within(float value, float low, float high) {
  return std::isfinite(value) && value >= low && value <= high;
}

}  // namespace

Result<void> validateStrandLooks(std::span<const HairStrandLook> looks, std::size_t strandCount) {
  if (looks.empty()) return {};
  if (looks.size() != strandCount)
    return fail(std::to_string(looks.size()) + " strand looks for " + std::to_string(strandCount) +
                " dense strands (expected one each, or none)");
  for (std::size_t s = 0; s < looks.size(); ++s) {
    const HairStrandLook& look = looks[s];
    const auto bad = [&](const std::string& what) {
      return fail("strand look " + std::to_string(s) + ": " + what);
    };
    if (!(std::isfinite(look.widthScale) && look.widthScale > 0.0f))
      return bad("the width factor must be finite and > 0, got " + std::to_string(look.widthScale));
    if (!within(look.tipWidthScale, 0.0f, 1.0f))
      return bad("the tip width factor must be in [0, 1], got " + std::to_string(look.tipWidthScale));
    if (!within(look.opacityScale, 0.0f, 1.0f))
      return bad("the opacity factor must be in [0, 1], got " + std::to_string(look.opacityScale));
    for (int c = 0; c < 3; ++c)
      if (!within(look.colour[c], 0.0f, 1.0f))
        return bad("colour component " + std::to_string(c) + " must be in [0, 1], got " +
                   std::to_string(look.colour[c]));
  }
  return {};
}

Buffer uploadStrandLooks(const Device& device, std::span<const HairStrandLook> looks, std::uint32_t strandCount) {
  std::vector<HairStrandLook> ones;
  if (looks.empty()) {
    ones.assign(std::max<std::uint32_t>(strandCount, 1), HairStrandLook{});
    looks = ones;
  }
  return Buffer::withData(device, std::as_bytes(looks), vk::BufferUsageFlagBits::eUniformTexelBuffer);
}

ShadowedLook shadowedLook(const HairGroomSettings& settings, std::span<const HairStrandLook> looks) {
  if (looks.empty()) return {settings.width, settings.opacity};
  double width = 0.0, opacity = 0.0;
  for (const HairStrandLook& look : looks) {
    width += look.widthScale;
    opacity += look.opacityScale;
  }
  const auto strands = static_cast<double>(looks.size());
  return {static_cast<float>(settings.width * width / strands), static_cast<float>(settings.opacity * opacity / strands)};
}

}  // namespace mane::render
