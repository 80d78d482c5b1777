#include "render/passes/hair_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "render/descriptors.hpp"
#include "render/passes/hair_lighting_pass.hpp"
#include "render/strand_looks.hpp"
#include "render/strand_lod.hpp"

namespace mane::render {
namespace {

// After the frame: the draws read their commands, and the host reads the choice (lastChoice).
constexpr ResourceUse kChoiceReadable{vk::PipelineStageFlagBits2::eDrawIndirect | vk::PipelineStageFlagBits2::eHost,
                                      vk::AccessFlagBits2::eIndirectCommandRead | vk::AccessFlagBits2::eHostRead};

// std140 mirror of HairUniforms in shaders/hair_uniforms.glsl.
struct HairUniforms {
  glm::mat4 viewProjection;
  glm::vec4 eye;
  glm::vec4 groom;
  glm::vec4 viewport;
  glm::uvec4 counts;
  glm::uvec4 occlusion;
  glm::vec4 levelOfDetail;
};
static_assert(sizeof(HairUniforms) == 64 + 6 * 16);

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

Result<void> validate(const HairGroomSettings& groom) {
  if (!(std::isfinite(groom.width) && groom.width > 0.0f))
    return fail("hair groom: width must be a finite number of metres > 0, got " + std::to_string(groom.width));
  if (!(groom.tipWidthScale >= 0.0f && groom.tipWidthScale <= 1.0f))
    return fail("hair groom: tipWidthScale must be in [0, 1], got " + std::to_string(groom.tipWidthScale));
  if (!(groom.opacity >= 0.0f && groom.opacity <= 1.0f))
    return fail("hair groom: opacity must be in [0, 1], got " + std::to_string(groom.opacity));
  if (!(std::isfinite(groom.minimumPixelWidth) && groom.minimumPixelWidth >= 0.25f))
    return fail("hair groom: minimumPixelWidth must be a finite number of pixels ≥ 0.25, got " +
                std::to_string(groom.minimumPixelWidth));
  if (!(std::isfinite(groom.lodPixelWidth) && groom.lodPixelWidth >= 0.0f))
    return fail("hair groom: lodPixelWidth must be a finite number of pixels ≥ 0, got " +
                std::to_string(groom.lodPixelWidth));
  return {};
}

// Sums and Primitives in shaders/hair_primitive.comp: VkDrawIndexedIndirectCommand twice, then
// the sums the strands add to and those the last choice was made from.
struct PrimitiveSums {
  std::uint32_t wideVertices;
  std::uint32_t widthLow, widthHigh;
  std::uint32_t lostLow, lostHigh;
  std::uint32_t hiddenVertices;
};
struct PrimitiveDraws {
  vk::DrawIndexedIndirectCommand ribbons;
  vk::DrawIndexedIndirectCommand lines;
  PrimitiveSums sums;
  PrimitiveSums chosen;
};
static_assert(sizeof(PrimitiveDraws) == 88, "std430 packs the shader's words without padding");
constexpr vk::DeviceSize kRibbonDrawOffset = offsetof(PrimitiveDraws, ribbons);
constexpr vk::DeviceSize kLineDrawOffset = offsetof(PrimitiveDraws, lines);
constexpr std::uint32_t kPrimitiveWorkgroup = 64;  // local_size_x of hair_primitive.comp
constexpr std::uint32_t kMaxWorkgroupsX = 65535;   // the least maxComputeWorkGroupCount[0]

// The ribbon indices, then the line indices, of every segment. Ribbons: two triangles per segment
// over the vertices 2 × (s × Nd + i) + side of hair.vert, counter-clockwise seen from the side the
// ribbon's s points to: (i, −)(i+1, −)(i+1, +) and (i, −)(i+1, +)(i, +). Lines: one per segment
// over s × Nd + i. The count fits 32 bits (setStrands checks), and so does every index, as
// 2·Nd ≤ 8·(Nd − 1).
Buffer strandIndices(const Device& device, std::uint32_t strands, std::uint32_t verticesPerStrand) {
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(strands) * (verticesPerStrand - 1) * 8);
  for (std::uint32_t k = 0; k < strands; ++k)
    for (std::uint32_t i = 0; i + 1 < verticesPerStrand; ++i) {
      const std::uint32_t minus = 2 * (k * verticesPerStrand + i), plus = minus + 1;
      const std::uint32_t nextMinus = minus + 2, nextPlus = minus + 3;
      indices.insert(indices.end(), {minus, nextMinus, nextPlus, minus, nextPlus, plus});
    }
  for (std::uint32_t k = 0; k < strands; ++k)
    for (std::uint32_t i = 0; i + 1 < verticesPerStrand; ++i)
      indices.insert(indices.end(), {k * verticesPerStrand + i, k * verticesPerStrand + i + 1});
  if (indices.empty()) indices.push_back(0);  // a zero-sized buffer is not allowed
  return Buffer::withData(device, std::as_bytes(std::span(indices)),
                          vk::BufferUsageFlagBits::eIndexBuffer | vk::BufferUsageFlagBits::eStorageBuffer);
}

}  // namespace

Result<std::unique_ptr<HairPass>> HairPass::create(const Device& device, const HairPassSettings& settings) {
  try {
    return std::unique_ptr<HairPass>(new HairPass(device, settings));
  } catch (const vk::SystemError& error) {
    return fail(std::string("hair pass: Vulkan error while creating the pipeline: ") + error.what());
  }
}

HairPass::HairPass(const Device& device, const HairPassSettings& settings)
    : device_(&device), analyticCoverage_(settings.samples == vk::SampleCountFlagBits::e1) {
  using Stage = vk::ShaderStageFlagBits;
  using Type = vk::DescriptorType;
  setLayout_ = makeSetLayout(device, {{Type::eUniformBuffer, Stage::eVertex | Stage::eFragment | Stage::eCompute},
                                      // 1–3, hair.vert's strands, alike: setStrands writes them in one update.
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eCompute},  // 4: draw order
                                      {Type::eStorageBuffer, Stage::eCompute},  // 5: PrimitiveDraws
                                      {Type::eStorageBuffer, Stage::eCompute},  // 6: opaque depth tiles
                                      {Type::eStorageBuffer, Stage::eCompute},  // 7: visible segments per strand
                                      {Type::eStorageBuffer, Stage::eCompute},  // 8: their bits
                                      {Type::eStorageBuffer, Stage::eCompute},  // 9: first segments in drawing order
                                      {Type::eStorageBuffer, Stage::eCompute},  // 10: the draws' indices
                                      {Type::eStorageBuffer, Stage::eCompute},  // 11: the vertices to shade
                                      {Type::eStorageBuffer, Stage::eCompute},  // 12: the lines' clip positions
                                      {Type::eStorageBuffer, Stage::eCompute},  // 13: and widths
                                      {Type::eUniformTexelBuffer, Stage::eCompute},  // 14: positions
                                      {Type::eUniformTexelBuffer, Stage::eCompute},  // 15: tangents
                                      // 16: the strands' looks
                                      {Type::eUniformTexelBuffer, Stage::eVertex | Stage::eCompute}});
  const bool depth = settings.depthFormat != vk::Format::eUndefined;
  // The lines' vertex attributes (hair_line.vert): clip position, width, radiance.
  std::vector<vk::VertexInputBindingDescription> lineBindings{{0, sizeof(glm::vec4), vk::VertexInputRate::eVertex},
                                                              {1, sizeof(glm::vec4), vk::VertexInputRate::eVertex},
                                                              {2, sizeof(glm::vec4), vk::VertexInputRate::eVertex}};
  std::vector<vk::VertexInputAttributeDescription> lineAttributes{{0, 0, vk::Format::eR32G32B32A32Sfloat, 0},
                                                                  {1, 1, vk::Format::eR32G32B32A32Sfloat, 0},
                                                                  {2, 2, vk::Format::eR32G32B32A32Sfloat, 0}};
  const auto drawPipeline = [&](bool lines) {
    return makeGraphicsPipeline(
        device, GraphicsPipelineSettings{
                    .vertexShader = lines ? "hair_line.vert" : "hair.vert",
                    .fragmentShader = lines ? "hair_line.frag" : "hair.frag",
                    .vertexBindings = lines ? lineBindings : std::vector<vk::VertexInputBindingDescription>{},
                    .vertexAttributes = lines ? lineAttributes : std::vector<vk::VertexInputAttributeDescription>{},
                    .topology = lines ? vk::PrimitiveTopology::eLineList : vk::PrimitiveTopology::eTriangleList,
                    .dynamicLineWidth = lines,
                    .cullMode = vk::CullModeFlagBits::eNone,
                    .colorFormats = {settings.colorFormat},
                    .blend = Blend::kPremultipliedAlpha,
                    .depthFormat = settings.depthFormat,
                    .depthTest = depth,
                    .depthWrite = false,
                    .samples = settings.samples,
                    .setLayouts = {*setLayout_},
                    .constants = {analyticCoverage_ ? 1u : 0u}});
  };
  ribbonPipeline_ = drawPipeline(false);
  linePipeline_ = drawPipeline(true);
  const std::uint32_t analytic = analyticCoverage_ ? 1u : 0u;
  countPipeline_ = makeComputePipeline(device, "hair_primitive.comp", setLayout_, 0, {0u, analytic});
  choosePipeline_ = makeComputePipeline(device, "hair_primitive.comp", setLayout_, 0, {1u, analytic});
  indexPipeline_ = makeComputePipeline(device, "hair_primitive.comp", setLayout_, 0, {2u, analytic});
  pool_ = makeDescriptorPool(device, 1,
                             {{Type::eUniformBuffer, 1}, {Type::eStorageBuffer, 13}, {Type::eUniformTexelBuffer, 3}});
  set_ = allocateSet(device, pool_, setLayout_);
  uniforms_ = Buffer(device, sizeof(HairUniforms), vk::BufferUsageFlagBits::eUniformBuffer,
                     vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  writeUniformBuffer(device, set_, 0, uniforms_);
  // Host-visible so that lastChoice() can read what the GPU chose.
  draws_ = Buffer(device, sizeof(PrimitiveDraws),
                  vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eIndirectBuffer,
                  vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  std::memset(draws_.mapped().data(), 0, sizeof(PrimitiveDraws));
  writeStorageBuffer(device, set_, 5, draws_);
  // Until setOcclusion: one tile over any screen, at the far plane, which hides nothing.
  const float farPlane = 1.0f;
  noOcclusion_ =
      Buffer::withData(device, std::as_bytes(std::span(&farPlane, 1)), vk::BufferUsageFlagBits::eStorageBuffer);
  setOcclusion(noOcclusion_, {.tiles = {1, 1}, .tileSize = std::numeric_limits<std::int32_t>::max()});
}

void HairPass::setOcclusion(const Buffer& tileMaxDepth, const HairOcclusionTiles& tiles) {
  writeStorageBuffer(*device_, set_, 6, tileMaxDepth);
  occlusionTiles_ = *tileMaxDepth.buffer();
  occlusion_ = tiles;
  writeOcclusionUniforms();
}

void HairPass::writeOcclusionUniforms() {
  const glm::uvec4 occlusion(occlusion_.tiles.x, occlusion_.tiles.y, occlusion_.tileSize, 0u);
  std::memcpy(uniforms_.mapped().data() + offsetof(HairUniforms, occlusion), &occlusion, sizeof(occlusion));
}

Result<void> HairPass::setStrands(const HairStrands& strands) {
  if (!strands.positions || !strands.tangents || !strands.radiance)
    return fail("hair strands: the position, tangent or radiance buffer is null");
  if (strands.verticesPerStrand < 2)
    return fail("hair strands: need at least 2 vertices per strand, got " + std::to_string(strands.verticesPerStrand));
  const std::uint64_t segments = std::uint64_t(strands.strandCount) * (strands.verticesPerStrand - 1);
  if (8 * segments > std::numeric_limits<std::uint32_t>::max())
    return fail("hair strands: " + std::to_string(strands.strandCount) + " strands × " +
                std::to_string(strands.verticesPerStrand) + " vertices need " + std::to_string(8 * segments) +
                " ribbon and line indices, more than a draw can reach (2^32 − 1)");

  const std::uint64_t vertices = std::uint64_t(strands.strandCount) * strands.verticesPerStrand;
  if (vertices > device_->limits().maxTexelBufferElements)
    return fail("hair strands: " + std::to_string(vertices) +
                " vertices are more than this device's texel buffers hold (" +
                std::to_string(device_->limits().maxTexelBufferElements) + ")");

  const std::array buffers{vk::DescriptorBufferInfo{.buffer = strands.positions, .offset = 0, .range = VK_WHOLE_SIZE},
                           vk::DescriptorBufferInfo{.buffer = strands.tangents, .offset = 0, .range = VK_WHOLE_SIZE},
                           vk::DescriptorBufferInfo{.buffer = strands.radiance, .offset = 0, .range = VK_WHOLE_SIZE}};
  device_->device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set_,
                                                                .dstBinding = 1,
                                                                .descriptorCount = 3,
                                                                .descriptorType = vk::DescriptorType::eStorageBuffer,
                                                                .pBufferInfo = buffers.data()},
                                         {});
  // Buffer order until setDrawOrder says otherwise.
  order_ = Buffer(*device_, std::max<vk::DeviceSize>(strands.strandCount, 1) * sizeof(std::uint32_t),
                  vk::BufferUsageFlagBits::eStorageBuffer,
                  vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  auto* order = reinterpret_cast<std::uint32_t*>(order_.mapped().data());
  for (std::uint32_t s = 0; s < strands.strandCount; ++s) order[s] = s;
  writeStorageBuffer(*device_, set_, 4, order_);
  indices_ = strandIndices(*device_, strands.strandCount, strands.verticesPerStrand);
  writeStorageBuffer(*device_, set_, 10, indices_);
  const vk::DeviceSize strandWords = std::max<vk::DeviceSize>(strands.strandCount, 1) * sizeof(std::uint32_t);
  const vk::DeviceSize segmentWords = (strands.verticesPerStrand + 30) / 32;
  visibleCounts_ =
      Buffer(*device_, strandWords, vk::BufferUsageFlagBits::eStorageBuffer, vk::MemoryPropertyFlagBits::eDeviceLocal);
  visibleBits_ = Buffer(*device_, strandWords * segmentWords, vk::BufferUsageFlagBits::eStorageBuffer,
                        vk::MemoryPropertyFlagBits::eDeviceLocal);
  firstSegments_ = Buffer(*device_, 2 * strandWords, vk::BufferUsageFlagBits::eStorageBuffer,
                          vk::MemoryPropertyFlagBits::eDeviceLocal);
  writeStorageBuffer(*device_, set_, 7, visibleCounts_);
  writeStorageBuffer(*device_, set_, 8, visibleBits_);
  writeStorageBuffer(*device_, set_, 9, firstSegments_);
  shadeList_ = HairLightingPass::everyVertex(*device_, static_cast<std::uint32_t>(vertices));
  writeStorageBuffer(*device_, set_, 11, shadeList_);
  const vk::BufferUsageFlags lineUsage =
      vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eVertexBuffer;
  const vk::DeviceSize lineVertices = std::max<vk::DeviceSize>(vertices, 1);
  lineClips_ = Buffer(*device_, lineVertices * sizeof(glm::vec4), lineUsage, vk::MemoryPropertyFlagBits::eDeviceLocal);
  lineWidths_ = Buffer(*device_, lineVertices * sizeof(glm::vec4), lineUsage, vk::MemoryPropertyFlagBits::eDeviceLocal);
  writeStorageBuffer(*device_, set_, 12, lineClips_);
  writeStorageBuffer(*device_, set_, 13, lineWidths_);
  positions_ = strands.positions;
  tangents_ = strands.tangents;
  radiance_ = strands.radiance;
  positionTexels_ = makeTexelView(*device_, strands.positions, vk::Format::eR32G32B32A32Sfloat);
  tangentTexels_ = makeTexelView(*device_, strands.tangents, vk::Format::eR32G32B32A32Sfloat);
  writeUniformTexelBuffer(*device_, set_, 14, positionTexels_);
  writeUniformTexelBuffer(*device_, set_, 15, tangentTexels_);
  strandCount_ = strands.strandCount;
  everyStrandPlain_ = uploadStrandLooks(*device_, {}, strands.strandCount);
  bindStrandLooks(everyStrandPlain_);
  indexCount_ = static_cast<std::uint32_t>(6 * segments);
  verticesPerStrand_ = strands.verticesPerStrand;
  PrimitiveDraws draws{};  // the sums start at zero
  draws.ribbons = vk::DrawIndexedIndirectCommand{.indexCount = indexCount_, .instanceCount = 1};
  draws.lines =
      vk::DrawIndexedIndirectCommand{.indexCount = static_cast<std::uint32_t>(2 * segments), .firstIndex = indexCount_};
  std::memcpy(draws_.mapped().data(), &draws, sizeof(draws));
  // Keep the uniforms of an earlier update in step (counts.x is the strands, y Nd, w the lines' first index).
  const std::array counts{strandCount_, verticesPerStrand_};
  std::memcpy(uniforms_.mapped().data() + offsetof(HairUniforms, counts), counts.data(), sizeof(counts));
  std::memcpy(uniforms_.mapped().data() + offsetof(HairUniforms, counts) + 3 * sizeof(std::uint32_t), &indexCount_,
              sizeof(indexCount_));
  return {};
}

Result<void> HairPass::setStrandLooks(const Buffer& looks) {
  const vk::DeviceSize needed = vk::DeviceSize(strandCount_) * sizeof(HairStrandLook);
  if (strandCount_ == 0 || looks.size() == 0 || looks.size() < needed)
    return fail("hair strand looks: " + std::to_string(strandCount_) + " strands need " + std::to_string(needed) +
                " bytes of looks, the buffer holds " + std::to_string(looks.size()));
  bindStrandLooks(looks);
  return {};
}

void HairPass::bindStrandLooks(const Buffer& looks) {
  // Written once when uploaded and only read since: no frame graph needs to order it.
  strandLookTexels_ = makeTexelView(*device_, *looks.buffer(), vk::Format::eR32G32B32A32Sfloat);
  writeUniformTexelBuffer(*device_, set_, 16, strandLookTexels_);
}

Result<void> HairPass::setDrawOrder(std::span<const std::uint32_t> order) {
  if (order.size() != strandCount_)
    return fail("hair draw order: " + std::to_string(order.size()) + " entries for " + std::to_string(strandCount_) +
                " strands");
  std::vector<bool> seen(strandCount_, false);
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (order[k] >= strandCount_ || seen[order[k]])
      return fail("hair draw order: entry " + std::to_string(k) + " (" + std::to_string(order[k]) +
                  ") is out of range or repeats a strand");
    seen[order[k]] = true;
  }
  std::memcpy(order_.mapped().data(), order.data(), order.size_bytes());
  return {};
}

Result<void> HairPass::update(const HairView& view, const HairGroomSettings& groom, float keptShare) {
  if (auto valid = validate(groom); !valid) return valid;
  if (!(keptShare >= kLeastKeptStrands && keptShare <= 1.0f))
    return fail("hair view: the share of strands kept must be in [1/16, 1], got " + std::to_string(keptShare));
  if (view.extent.width == 0 || view.extent.height == 0) return fail("hair view: the extent is empty");
  const float determinant = glm::determinant(view.viewProjection);
  if (!finite(view.viewProjection) || !std::isfinite(determinant) || determinant == 0.0f)
    return fail("hair view: the view-projection matrix is not finite and invertible");

  HairUniforms uniforms{};
  uniforms.viewProjection = view.viewProjection;
  uniforms.eye = hairEye(view.viewProjection);
  uniforms.groom = glm::vec4(groom.width, groom.tipWidthScale, groom.opacity, groom.minimumPixelWidth);
  const float lineWidth = drawnLineWidth(groom.minimumPixelWidth);
  uniforms.viewport = glm::vec4(float(view.extent.width), float(view.extent.height), lineWidth, 0.0f);
  uniforms.counts = glm::uvec4(strandCount_, verticesPerStrand_, linesDrawable(lineWidth) ? 1u : 0u, indexCount_);
  uniforms.levelOfDetail = glm::vec4(keptShare, 1.0f / keptShare, 0.0f, 0.0f);
  std::memcpy(uniforms_.mapped().data(), &uniforms, sizeof(uniforms));
  writeOcclusionUniforms();
  extent_ = view.extent;
  lineWidth_ = lineWidth;
  keptShare_ = keptShare;
  return {};
}

Result<void> HairPass::update(const FrameInput& frame, vk::Extent2D extent, const HairGroomSettings& groom,
                              float keptShare) {
  if (extent.width == 0 || extent.height == 0) return fail("hair view: the extent is empty");
  const float aspect = float(extent.width) / float(extent.height);
  return update(HairView{frame.camera.projection(aspect) * frame.camera.view(), extent}, groom, keptShare);
}

float HairPass::drawnLineWidth(float minimumPixelWidth) const {
  if (!analyticCoverage_) return minimumPixelWidth;
  // A pixel's reach past the strand's edge is at most half its diagonal (hair_coverage.glsl), on
  // each side; rounded up to a width the device draws.
  const float width = minimumPixelWidth + std::sqrt(2.0f);
  const float granularity = device_->limits().lineWidthGranularity;
  return granularity > 0.0f ? std::ceil(width / granularity) * granularity : width;
}

bool HairPass::linesDrawable(float width) const {
  const vk::PhysicalDeviceLimits& limits = device_->limits();
  if (limits.strictLines != VK_TRUE) return false;  // parallelograms: their area depends on the slope
  if (width == 1.0f) return true;
  return device_->wideLines() && width >= limits.lineWidthRange[0] && width <= limits.lineWidthRange[1];
}

void HairPass::declare(FrameGraph::Builder& pass) const {
  if (indexCount_ == 0 || extent_.width == 0) return;
  const auto compute = vk::PipelineStageFlagBits2::eComputeShader;
  pass.read(GraphResource(positions_), ResourceUse::sampled(compute));  // texel buffers
  pass.read(GraphResource(tangents_), ResourceUse::sampled(compute));
  pass.read(GraphResource(occlusionTiles_), ResourceUse::storageRead(compute));
  // The sums the previous choice zeroed are read, then written; the draws read indices, commands
  // and line vertices that these steps write again.
  pass.write(draws_, ResourceUse::storageReadWrite(compute));
  for (const Buffer* buffer : {&visibleCounts_, &visibleBits_, &firstSegments_, &shadeList_})
    pass.write(*buffer, ResourceUse::storageReadWrite(compute));
  for (const Buffer* buffer : {&indices_, &lineClips_, &lineWidths_})
    pass.write(*buffer, ResourceUse::storageWrite(compute));
}

void HairPass::execute(const vk::raii::CommandBuffer& commands) const {
  if (indexCount_ == 0 || extent_.width == 0) return;
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  // Each step reads what the one before wrote.
  const vk::MemoryBarrier2 stepDone{.srcStageMask = Stage::eComputeShader,
                                    .srcAccessMask = Access::eShaderStorageWrite,
                                    .dstStageMask = Stage::eComputeShader,
                                    .dstAccessMask = Access::eShaderStorageRead | Access::eShaderStorageWrite};
  const std::uint32_t groups = (strandCount_ + kPrimitiveWorkgroup - 1) / kPrimitiveWorkgroup;
  const std::uint32_t groupsX = std::min(groups, kMaxWorkgroupsX);
  const auto step = [&](const Pipeline& pipeline, std::uint32_t x, std::uint32_t y) {
    commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
    commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, {*set_}, {});
    commands.dispatch(x, y, 1);
  };
  step(countPipeline_, groupsX, (groups + groupsX - 1) / groupsX);
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &stepDone});
  step(choosePipeline_, 1, 1);
  commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &stepDone});
  step(indexPipeline_, groupsX, (groups + groupsX - 1) / groupsX);
}

void HairPass::record(const vk::raii::CommandBuffer& commands) const {
  if (indexCount_ == 0 || extent_.width == 0) return;
  // HairLightingPass reads the shade list as texels and as its dispatch's size.
  const ResourceUse shading{vk::PipelineStageFlagBits2::eComputeShader | vk::PipelineStageFlagBits2::eDrawIndirect,
                            vk::AccessFlagBits2::eShaderSampledRead | vk::AccessFlagBits2::eIndirectCommandRead};
  FrameGraph::recordAlone(commands, PassName::kHairLighting, *this,
                          {{shadeList_, shading},
                           {indices_, ResourceUse::indexInput()},
                           {lineClips_, ResourceUse::vertexInput()},
                           {lineWidths_, ResourceUse::vertexInput()},
                           {draws_, kChoiceReadable}});
}

void HairPass::declareDraw(FrameGraph::Builder& pass) const {
  if (indexCount_ == 0 || extent_.width == 0) return;
  const auto vertexShader = vk::PipelineStageFlagBits2::eVertexShader;
  pass.read(GraphResource(positions_), ResourceUse::storageRead(vertexShader));
  pass.read(GraphResource(tangents_), ResourceUse::storageRead(vertexShader));
  pass.read(GraphResource(radiance_), ResourceUse::storageRead(vertexShader));
  pass.read(GraphResource(radiance_), ResourceUse::vertexInput());  // the lines' third attribute
  pass.read(draws_, ResourceUse::indirectCommands());
  pass.read(indices_, ResourceUse::indexInput());
  pass.read(lineClips_, ResourceUse::vertexInput());
  pass.read(lineWidths_, ResourceUse::vertexInput());
}

void HairPass::leaveChoiceReadable(FrameGraph& graph) const {
  if (indexCount_ == 0 || extent_.width == 0) return;
  graph.leaveAs(draws_, kChoiceReadable);
}

HairPrimitiveChoice HairPass::lastChoice() const {
  PrimitiveDraws draws{};
  std::memcpy(&draws, draws_.mapped().data(), sizeof(draws));
  const auto sum = [](std::uint32_t low, std::uint32_t high) { return std::ldexp(double(high), 32) + low; };
  const PrimitiveSums& chosen = draws.chosen;
  const double width = sum(chosen.widthLow, chosen.widthHigh);
  return {.primitive = draws.lines.instanceCount != 0 ? HairPrimitive::kLines : HairPrimitive::kRibbons,
          .wideVertices = chosen.wideVertices,
          .uncoveredByLines = width > 0.0 ? sum(chosen.lostLow, chosen.lostHigh) / width : 0.0,
          .hiddenVertices = chosen.hiddenVertices,
          .keptShare = keptShare_};
}

void HairPass::draw(const vk::raii::CommandBuffer& commands) const {
  if (indexCount_ == 0 || extent_.width == 0) return;
  // Both draws are recorded; the choice made by record() gives one of them no instance.
  commands.bindIndexBuffer(*indices_.buffer(), 0, vk::IndexType::eUint32);
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *ribbonPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *ribbonPipeline_.layout, 0, {*set_}, {});
  setViewportAndScissor(commands, extent_);
  commands.drawIndexedIndirect(*draws_.buffer(), kRibbonDrawOffset, 1, sizeof(vk::DrawIndexedIndirectCommand));
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *linePipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *linePipeline_.layout, 0, {*set_}, {});
  commands.setLineWidth(lineWidth_);
  commands.bindVertexBuffers(0, {*lineClips_.buffer(), *lineWidths_.buffer(), radiance_}, {0, 0, 0});
  commands.drawIndexedIndirect(*draws_.buffer(), kLineDrawOffset, 1, sizeof(vk::DrawIndexedIndirectCommand));
}

}  // namespace mane::render
