#pragma once
// What the hair pass tests share (hair_pass_test.cpp, hair_strand_looks_test.cpp): strands laid
// out as the passes read them, an orthographic view, a fixture that shades and draws them into an
// HDR target and reads it back, and the parallel strands whose coverage is known exactly.

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/luts/marschner.hpp"
#include "render/luts/marschner_lut.hpp"
#include "render/passes/hair_lighting_pass.hpp"
#include "render/passes/hair_pass.hpp"
#include "render/passes/hair_shadow_pass.hpp"
#include "render/render_target.hpp"
#include "render/strand_looks.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render::hair_fixture {

/// Strands laid out as the pass reads them: positions (w = t) and tangents, strand-major.
struct StrandData {
  std::vector<glm::vec4> positions;
  std::vector<glm::vec4> tangents;
  std::uint32_t verticesPerStrand = 0;
  std::uint32_t strandCount() const { return std::uint32_t(positions.size() / verticesPerStrand); }
};

/// Straight strand from `root` to `tip` with `vertices` evenly spaced vertices.
inline void addStraightStrand(StrandData& data, glm::vec3 root, glm::vec3 tip, std::uint32_t vertices) {
  data.verticesPerStrand = vertices;
  const glm::vec3 tangent = glm::normalize(tip - root);
  for (std::uint32_t i = 0; i < vertices; ++i) {
    const float t = float(i) / float(vertices - 1);
    data.positions.emplace_back(glm::mix(root, tip, t), t);
    data.tangents.emplace_back(tangent, 0.0f);
  }
}

/// Orthographic world → clip seen from +z: `metresPerPixel` at `extent`, centred on the origin,
/// Vulkan's Y flip as Camera::projection does.
inline glm::mat4 orthographicView(vk::Extent2D extent, float metresPerPixel) {
  const float halfWidth = 0.5f * metresPerPixel * float(extent.width);
  const float halfHeight = 0.5f * metresPerPixel * float(extent.height);
  glm::mat4 projection = glm::orthoRH_ZO(-halfWidth, halfWidth, -halfHeight, halfHeight, 0.01f, 3.0f);
  projection[1][1] = -projection[1][1];
  return projection * glm::lookAtRH(glm::vec3(0, 0, 1), glm::vec3(0), glm::vec3(0, 1, 0));
}

/// Linear RGBA of the resolved HDR image, rows top to bottom.
using Pixels = std::vector<glm::vec4>;

class HairPassTest : public mane::testing::VulkanTest {
public:
  MarschnerLut& lut(const HairShadingParams& params) {
    auto created = MarschnerLut::create(device(), params);
    if (!created) throw std::runtime_error(created.error().message);
    luts_.push_back(std::make_unique<MarschnerLut>(std::move(*created)));
    return *luts_.back();
  }

  /// Shades `data` without shadows, then draws it over a transparent black background (alpha
  /// 0) and depth 1 as seen by `view`, and returns the pixels.
  Pixels render(const MarschnerLut& table, const StrandData& data, vk::SampleCountFlagBits samples,
                const HairView& view, std::span<const DirectionalLight> lights, glm::vec3 ambient,
                const HairGroomSettings& groom) {
    auto pass = HairPass::create(
        device(),
        {.colorFormat = RenderTarget::kHdrFormat, .depthFormat = RenderTarget::kDepthFormat, .samples = samples});
    EXPECT_TRUE(pass.has_value()) << pass.error().message;
    const auto usage = vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer;
    const Buffer positions = Buffer::withData(device(), std::as_bytes(std::span(data.positions)), usage);
    const Buffer tangents = Buffer::withData(device(), std::as_bytes(std::span(data.tangents)), usage);
    auto shadows = HairShadowPass::create(device());
    EXPECT_TRUE(shadows.has_value()) << shadows.error().message;
    auto lighting = HairLightingPass::create(device(), table, **shadows, positions, tangents, data.strandCount(),
                                             data.verticesPerStrand);
    EXPECT_TRUE(lighting.has_value()) << lighting.error().message;
    const auto set = (*pass)->setStrands({.positions = *positions.buffer(),
                                          .tangents = *tangents.buffer(),
                                          .radiance = *(*lighting)->radiance().buffer(),
                                          .strandCount = data.strandCount(),
                                          .verticesPerStrand = data.verticesPerStrand});
    EXPECT_TRUE(set.has_value()) << set.error().message;
    (*lighting)->setShadeList((*pass)->shadeList());
    std::optional<Buffer> strandLooks;
    if (!looks.empty()) {
      strandLooks = uploadStrandLooks(device(), looks, data.strandCount());
      const auto drawn = (*pass)->setStrandLooks(*strandLooks);
      EXPECT_TRUE(drawn.has_value()) << drawn.error().message;
      const auto shaded = (*lighting)->setStrandLooks(*strandLooks);
      EXPECT_TRUE(shaded.has_value()) << shaded.error().message;
    }
    std::optional<Buffer> tiles;
    if (occlusion) {
      tiles = Buffer::withData(device(), std::as_bytes(std::span(occlusion->first)),
                               vk::BufferUsageFlagBits::eStorageBuffer);
      (*pass)->setOcclusion(*tiles, occlusion->second);
    }
    const auto lit = (*lighting)->update(view.viewProjection, lights, ambient, (*shadows)->uniforms());
    EXPECT_TRUE(lit.has_value()) << lit.error().message;
    const auto updated = (*pass)->update(view, groom, keptShare);
    EXPECT_TRUE(updated.has_value()) << updated.error().message;

    const vk::Extent2D extent = view.extent;
    const RenderTarget target(device(), {.extent = extent, .samples = samples});
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      using Layout = vk::ImageLayout;
      using Stage = vk::PipelineStageFlagBits2;
      using Access = vk::AccessFlagBits2;
      (*pass)->record(commands);  // first: it lists the vertices to shade
      (*lighting)->record(commands);
      target.beginScene(commands, glm::vec4(0.0f));
      (*pass)->draw(commands);
      commands.endRendering();
      transition(commands, target.hdr(), Layout::eColorAttachmentOptimal, Layout::eTransferSrcOptimal,
                 Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eTransfer, Access::eTransferRead);
    });
    lastChoice = (*pass)->lastChoice();
    const std::vector<std::byte> bytes = readBack(device(), target.hdr(), 8);
    Pixels pixels(std::size_t(extent.width) * extent.height);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      std::array<std::uint16_t, 4> halves{};
      std::memcpy(halves.data(), bytes.data() + 8 * i, 8);
      for (int c = 0; c < 4; ++c) pixels[i][c] = glm::unpackHalf1x16(halves[c]);
    }
    return pixels;
  }

  /// What the pass drew in the last `render`.
  HairPrimitiveChoice lastChoice;
  /// The strands' own looks for `render` (HairPass and HairLightingPass::setStrandLooks); none
  /// when empty.
  std::vector<HairStrandLook> looks;
  /// Opaque depth per tile for `render` to hide strands behind (HairPass::setOcclusion); none
  /// when empty.
  std::optional<std::pair<std::vector<float>, HairOcclusionTiles>> occlusion;
  /// The share of the strands `render` draws (HairPass::update, "Level of detail").
  float keptShare = 1.0f;

private:
  std::vector<std::unique_ptr<MarschnerLut>> luts_;
};

inline constexpr vk::Extent2D kCoverageExtent{128, 128};
inline constexpr float kMetresPerPixel = 1e-3f;
inline constexpr int kStrands = 10;
inline constexpr float kLengthPixels = 100.0f;

// Ten vertical strands (tangent +y, seen head-on along −z), 100 pixels long, 12 pixels apart.
// Their centres sit at fractional pixel offsets 0.05, 0.15, … 0.95: the rasteriser counts pixel
// centres (or samples), and over ten offsets spaced 1/10 an interval of width w holds exactly
// round-to-tenths(w) of them on average, so a width in whole tenths of a pixel is reproduced
// exactly by counting. The ends sit a quarter pixel off the pixel boundaries so that exactly 100
// rows are crossed. The ribbon ends are flat: each strand's projected area is width × length.
inline StrandData parallelStrands() {
  StrandData data;
  for (int i = 0; i < kStrands; ++i) {
    const float xPixels = -60.0f + 12.0f * float(i) + 0.05f + 0.1f * float(i);
    const float x = xPixels * kMetresPerPixel;
    const float y0 = (-50.0f + 0.25f) * kMetresPerPixel;
    addStraightStrand(data, {x, y0, 0.0f}, {x, y0 + kLengthPixels * kMetresPerPixel, 0.0f}, 9);
  }
  return data;
}

struct Coverage {
  double sum = 0.0;      ///< Σ alpha, pixels
  float largest = 0.0f;  ///< the largest alpha of any pixel
  std::size_t lit = 0;   ///< pixels with alpha > 0
};

inline Coverage measureCoverage(const Pixels& pixels) {
  Coverage coverage;
  for (const glm::vec4& pixel : pixels) {
    coverage.sum += pixel.a;
    coverage.largest = std::max(coverage.largest, pixel.a);
    if (pixel.a > 0.0f) ++coverage.lit;
  }
  return coverage;
}

}  // namespace mane::render::hair_fixture
