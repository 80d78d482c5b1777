// A triangle rendered through the whole plumbing (pipeline from embedded SPIR-V, dynamic
// rendering into the RGBA16F target, MSAA resolve, read-back) and checked pixel by pixel
// against its analytic coverage.
//
// Oracle: Vulkan's rasterization rule. A sample is covered when it lies inside the triangle's
// three edge functions. Without MSAA the sample is the pixel centre; with 4x MSAA the samples
// sit at the standard locations (1/8 units: (3,1) (7,3) (1,5) (5,7)) and the resolved value is
// the covered fraction. Vertices are chosen so no edge passes exactly through a sample, so the
// tie-breaking rule never matters and the expected image is exact. The vertices lie on the
// 1/16-pixel grid and the 64x64 viewport makes clip→pixel exact in binary, so the rasterizer's
// sub-pixel snapping (8 bits on lavapipe) does not move them.

#include <array>
#include <cstring>

#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "render/pipelines.hpp"
#include "render/render_target.hpp"
#include "tests/support/vulkan_fixture.hpp"

namespace mane::render {
namespace {

constexpr vk::Extent2D kExtent{64, 64};
// Pixel coordinates (5 3/16, 9 5/16), (57 11/16, 20 7/16), (22 13/16, 61 1/16) in clip space;
// winding is irrelevant: culling is off. The nearest sample is 0.023 px² (edge-function units)
// from any edge.
constexpr std::array<glm::vec2, 3> kTriangle{glm::vec2(-0.837890625f, -0.708984375f),
                                             glm::vec2(0.802734375f, -0.361328125f),
                                             glm::vec2(-0.287109375f, 0.908203125f)};
constexpr glm::vec4 kColor{1.0f, 0.5f, 0.25f, 1.0f};

glm::vec2 toPixels(glm::vec2 clip) {
  return {(clip.x * 0.5f + 0.5f) * float(kExtent.width), (clip.y * 0.5f + 0.5f) * float(kExtent.height)};
}

bool inside(glm::vec2 point) {
  const glm::vec2 a = toPixels(kTriangle[0]), b = toPixels(kTriangle[1]), c = toPixels(kTriangle[2]);
  auto edge = [](glm::vec2 p, glm::vec2 q, glm::vec2 r) {
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
  };
  const double e0 = edge(a, b, point), e1 = edge(b, c, point), e2 = edge(c, a, point);
  return (e0 > 0 && e1 > 0 && e2 > 0) || (e0 < 0 && e1 < 0 && e2 < 0);
}

// Renders the triangle and returns the resolved RGBA16F texels as floats.
std::vector<glm::vec4> renderTriangle(const Device& device, vk::SampleCountFlagBits samples) {
  const RenderTarget target(device, {.extent = kExtent, .samples = samples});
  const Pipeline pipeline = makeGraphicsPipeline(
      device, GraphicsPipelineSettings{.vertexShader = "flat_color.vert",
                                       .fragmentShader = "flat_color.frag",
                                       .vertexBindings = {{.binding = 0, .stride = sizeof(glm::vec2)}},
                                       .vertexAttributes = {{0, 0, vk::Format::eR32G32Sfloat, 0}},
                                       .colorFormats = {RenderTarget::kHdrFormat},
                                       .samples = samples,
                                       .pushConstants = {{vk::ShaderStageFlagBits::eFragment, 0, sizeof(glm::vec4)}}});
  const Buffer vertices =
      Buffer::withData(device, std::as_bytes(std::span(kTriangle)), vk::BufferUsageFlagBits::eVertexBuffer);
  using Layout = vk::ImageLayout;
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    transition(commands, target.sceneColor(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eNone,
               Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
    if (target.multisampled())
      transition(commands, target.hdr(), Layout::eUndefined, Layout::eColorAttachmentOptimal, Stage::eNone,
                 Access::eNone, Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite);
    vk::RenderingAttachmentInfo color{.imageView = *target.sceneColor().view(),
                                      .imageLayout = Layout::eColorAttachmentOptimal,
                                      .loadOp = vk::AttachmentLoadOp::eClear,
                                      .storeOp = vk::AttachmentStoreOp::eStore,
                                      .clearValue = {.color = {.float32 = std::array{0.0f, 0.0f, 0.0f, 0.0f}}}};
    if (target.multisampled()) {
      color.resolveMode = vk::ResolveModeFlagBits::eAverage;
      color.resolveImageView = *target.hdr().view();
      color.resolveImageLayout = Layout::eColorAttachmentOptimal;
    }
    commands.beginRendering(vk::RenderingInfo{
        .renderArea = {.extent = kExtent}, .layerCount = 1, .colorAttachmentCount = 1, .pColorAttachments = &color});
    setViewportAndScissor(commands, kExtent);
    commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline.pipeline);
    commands.pushConstants<glm::vec4>(*pipeline.layout, vk::ShaderStageFlagBits::eFragment, 0, kColor);
    commands.bindVertexBuffers(0, {*vertices.buffer()}, {vk::DeviceSize{0}});
    commands.draw(3, 1, 0, 0);
    commands.endRendering();
    transition(commands, target.hdr(), Layout::eColorAttachmentOptimal, Layout::eTransferSrcOptimal,
               Stage::eColorAttachmentOutput, Access::eColorAttachmentWrite, Stage::eTransfer, Access::eTransferRead);
  });
  const auto bytes = readBack(device, target.hdr(), 8);
  std::vector<glm::vec4> texels(kExtent.width * kExtent.height);
  for (std::size_t i = 0; i < texels.size(); ++i) {
    std::uint64_t packed;
    std::memcpy(&packed, bytes.data() + i * 8, 8);
    texels[i] = glm::unpackHalf4x16(packed);
  }
  return texels;
}

class Triangle : public testing::VulkanTest {};

TEST_F(Triangle, SingleSampleCoverageMatchesPixelCentres) {
  const auto texels = renderTriangle(device(), vk::SampleCountFlagBits::e1);
  int covered = 0;
  for (std::uint32_t y = 0; y < kExtent.height; ++y)
    for (std::uint32_t x = 0; x < kExtent.width; ++x) {
      const bool expected = inside({x + 0.5f, y + 0.5f});
      covered += expected;
      // Exact: 1, 0.5 and 0.25 are representable in half floats.
      EXPECT_EQ(texels[y * kExtent.width + x], expected ? kColor : glm::vec4(0.0f)) << "pixel " << x << "," << y;
    }
  EXPECT_GT(covered, 500);  // the triangle is large enough for the check to mean something
}

TEST_F(Triangle, FourSamplesResolveToTheCoveredFraction) {
  const auto texels = renderTriangle(device(), vk::SampleCountFlagBits::e4);
  constexpr std::array<glm::vec2, 4> kSamples{glm::vec2(0.375f, 0.125f), glm::vec2(0.875f, 0.375f),
                                              glm::vec2(0.125f, 0.625f), glm::vec2(0.625f, 0.875f)};
  int partial = 0;
  for (std::uint32_t y = 0; y < kExtent.height; ++y)
    for (std::uint32_t x = 0; x < kExtent.width; ++x) {
      int hits = 0;
      for (const glm::vec2& sample : kSamples) hits += inside({x + sample.x, y + sample.y});
      partial += (hits > 0 && hits < 4);
      const glm::vec4 expected = kColor * (float(hits) / 4.0f);
      // The average of 4 half-float samples; 1e-3 covers the half rounding of 0.0625 steps.
      const glm::vec4 actual = texels[y * kExtent.width + x];
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(actual[c], expected[c], 1e-3) << "pixel " << x << "," << y;
    }
  EXPECT_GT(partial, 50);  // edges cross many pixels: the resolve is really exercised
}

}  // namespace
}  // namespace mane::render
