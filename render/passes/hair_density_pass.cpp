#include "render/passes/hair_density_pass.hpp"

#include <algorithm>
#include <array>
#include <numbers>
#include <string>

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

constexpr std::uint32_t kSplatWorkgroup = 64;      // local_size_x of shaders/hair_density_splat.comp
constexpr std::uint32_t kVisibilityWorkgroup = 4;  // local_size_x, _y and _z of shaders/hair_visibility.comp
constexpr float kFixedOne = 1048576.0f;            // 2²⁰: the density's units per unit optical depth

// Push constants of shaders/hair_density_splat.comp.
struct SplatConstants {
  glm::vec4 grid;     // xyz: the grid's lowest corner, metres; w: voxels per metre
  glm::uvec4 voxels;  // xyz: voxels along each axis
  glm::uvec4 counts;  // x: segments, y: vertices per strand
  glm::vec4 depth;    // x: fixed-point units of optical depth across a voxel per metre of fibre
};

// Push constants of shaders/hair_visibility.comp.
struct VisibilityConstants {
  glm::uvec4 voxels;  // xyz: voxels along each axis; w: voxels marched
};

}  // namespace

Image clearedVisibilityVolume(const Device& device, std::uint32_t side) {
  using Usage = vk::ImageUsageFlagBits;
  Image image(device, {.extent = {side, side},
                       .format = vk::Format::eR16G16B16A16Sfloat,
                       .usage = Usage::eStorage | Usage::eSampled | Usage::eTransferDst | Usage::eTransferSrc,
                       .depth = side});
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    using Stage = vk::PipelineStageFlagBits2;
    using Access = vk::AccessFlagBits2;
    using Layout = vk::ImageLayout;
    transition(commands, image, Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone, {}, Stage::eClear,
               Access::eTransferWrite);
    commands.clearColorImage(*image.image(), Layout::eTransferDstOptimal,
                             vk::ClearColorValue(std::array{0.0f, 0.0f, 0.0f, 0.0f}),
                             vk::ImageSubresourceRange{vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1});
    transition(commands, image, Layout::eTransferDstOptimal, Layout::eShaderReadOnlyOptimal, Stage::eClear,
               Access::eTransferWrite, Stage::eAllCommands, Access::eShaderSampledRead);
  });
  return image;
}

vk::raii::Sampler makeVisibilitySampler(const Device& device) {
  const auto border = vk::SamplerAddressMode::eClampToBorder;
  return vk::raii::Sampler(device.device(),
                           vk::SamplerCreateInfo{.magFilter = vk::Filter::eLinear,
                                                 .minFilter = vk::Filter::eLinear,
                                                 .mipmapMode = vk::SamplerMipmapMode::eNearest,
                                                 .addressModeU = border,
                                                 .addressModeV = border,
                                                 .addressModeW = border,
                                                 .borderColor = vk::BorderColor::eFloatTransparentBlack});
}

HairDensityPass::HairDensityPass(const Device& device) {
  using Type = vk::DescriptorType;
  const auto compute = vk::ShaderStageFlags(vk::ShaderStageFlagBits::eCompute);
  constexpr std::uint32_t voxels = kResolution * kResolution * kResolution;
  density_ = Buffer(device, vk::DeviceSize(voxels) * sizeof(std::uint32_t),
                    vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eUniformTexelBuffer |
                        vk::BufferUsageFlagBits::eTransferDst | vk::BufferUsageFlagBits::eTransferSrc,
                    vk::MemoryPropertyFlagBits::eDeviceLocal);
  densityTexels_ = makeTexelView(device, *density_.buffer(), vk::Format::eR32Uint);
  occlusion_ = clearedVisibilityVolume(device, kResolution);
  sampler_ = makeVisibilitySampler(device);
  splatLayout_ = makeSetLayout(device, {{Type::eUniformTexelBuffer, compute}, {Type::eStorageBuffer, compute}});
  visibilityLayout_ = makeSetLayout(device, {{Type::eUniformTexelBuffer, compute}, {Type::eStorageImage, compute}});
  splat_ = makeComputePipeline(device, "hair_density_splat.comp", splatLayout_, sizeof(SplatConstants));
  visibility_ = makeComputePipeline(device, "hair_visibility.comp", visibilityLayout_, sizeof(VisibilityConstants));
}

Result<std::unique_ptr<HairDensityPass>> HairDensityPass::create(const Device& device,
                                                                 std::span<const HairShadowPass::Groom> grooms) {
  if (grooms.empty()) return fail("hair density: no grooms");
  for (std::size_t g = 0; g < grooms.size(); ++g) {
    const OpacityShadowStrands& strands = grooms[g].strands;
    if (!strands.positions || strands.strandCount == 0 || strands.verticesPerStrand < 2)
      return fail("hair density: groom " + std::to_string(g) + " has no strands of two vertices or more");
  }
  try {
    std::unique_ptr<HairDensityPass> pass(new HairDensityPass(device));
    using Type = vk::DescriptorType;
    const auto sets = static_cast<std::uint32_t>(grooms.size()) + 1;
    pass->pool_ = makeDescriptorPool(
        device, sets, {{Type::eUniformTexelBuffer, sets}, {Type::eStorageBuffer, sets - 1}, {Type::eStorageImage, 1}});
    pass->visibilitySet_ = allocateSet(device, pass->pool_, pass->visibilityLayout_);
    writeUniformTexelBuffer(device, pass->visibilitySet_, 0, pass->densityTexels_);
    writeStorageImage(device, pass->visibilitySet_, 1, pass->occlusion_.view());
    for (const HairShadowPass::Groom& groom : grooms) {
      GroomSplat splat{
          .positions = groom.strands.positions,
          .segments = groom.strands.strandCount * (groom.strands.verticesPerStrand - 1),
          .verticesPerStrand = groom.strands.verticesPerStrand,
          .depthPerMetre = groom.extinction * groom.opacity * groom.width * float(std::numbers::pi) / 4.0f};
      splat.positionTexels = makeTexelView(device, *groom.strands.positions->buffer(), vk::Format::eR32G32B32A32Sfloat);
      splat.set = allocateSet(device, pass->pool_, pass->splatLayout_);
      writeUniformTexelBuffer(device, splat.set, 0, splat.positionTexels);
      writeStorageBuffer(device, splat.set, 1, pass->density_);
      pass->grooms_.push_back(std::move(splat));
    }
    return pass;
  } catch (const std::exception& error) {
    return fail(std::string("hair density: ") + error.what());
  }
}

void HairDensityPass::place(std::span<const HairBounds> bounds) {
  HairBounds all;
  for (std::size_t g = 0; g < grooms_.size(); ++g) {
    grooms_[g].placed = g < bounds.size() && !bounds[g].empty();
    if (!grooms_[g].placed) continue;
    all.low = all.empty() ? bounds[g].low : glm::min(all.low, bounds[g].low);
    all.high = all.empty() ? bounds[g].high : glm::max(all.high, bounds[g].high);
  }
  placement_.scale.w = 0.0f;
  if (all.empty()) return;
  // A voxel to spare on every side, so that the hair's outermost voxels fade to the border's
  // "nothing hidden" over a whole voxel rather than being cut.
  const glm::vec3 extent = glm::max(all.high - all.low, glm::vec3(1e-3f));
  voxelSide_ = std::max({extent.x, extent.y, extent.z}) / float(kResolution - 2);
  voxels_ = glm::min(glm::uvec3(glm::ceil(extent / voxelSide_)) + 2u, glm::uvec3(kResolution));
  // The grid fills the image's lowest corner; the visibility pass zeroes the rest.
  placement_.origin = glm::vec4(0.5f * (all.low + all.high) - 0.5f * glm::vec3(voxels_) * voxelSide_, 0.0f);
  placement_.scale = glm::vec4(glm::vec3(1.0f / (float(kResolution) * voxelSide_)), 1.0f);
}

void HairDensityPass::declareClear(FrameGraph::Builder& pass) const {
  pass.write(density_, ResourceUse::transferDestination());
}

void HairDensityPass::executeClear(const vk::raii::CommandBuffer& commands) const {
  commands.fillBuffer(*density_.buffer(), 0, VK_WHOLE_SIZE, 0u);
}

void HairDensityPass::declareSplat(FrameGraph::Builder& pass) const {
  const auto compute = vk::PipelineStageFlagBits2::eComputeShader;
  for (const GroomSplat& groom : grooms_)
    if (groom.placed) pass.read(*groom.positions, ResourceUse::sampled(compute));
  pass.write(density_, ResourceUse::storageReadWrite(compute));
}

void HairDensityPass::executeSplat(const vk::raii::CommandBuffer& commands) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *splat_.pipeline);
  const float voxel = voxelSide_;
  for (const GroomSplat& groom : grooms_) {
    if (!groom.placed) continue;
    commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *splat_.layout, 0, {*groom.set}, {});
    const SplatConstants constants{
        .grid = glm::vec4(glm::vec3(placement_.origin), 1.0f / voxel),
        .voxels = glm::uvec4(voxels_, 0u),
        .counts = glm::uvec4(groom.segments, groom.verticesPerStrand, 0u, 0u),
        .depth = glm::vec4(kFixedOne * groom.depthPerMetre / (voxel * voxel), 0.0f, 0.0f, 0.0f)};
    commands.pushConstants<SplatConstants>(*splat_.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
    commands.dispatch((groom.segments + kSplatWorkgroup - 1) / kSplatWorkgroup, 1, 1);
  }
}

void HairDensityPass::declareVisibility(FrameGraph::Builder& pass) const {
  const auto compute = vk::PipelineStageFlagBits2::eComputeShader;
  pass.read(density_, ResourceUse::sampled(compute));
  pass.write(occlusion_, ResourceUse::storageWrite(compute), Contents::kDiscard);
}

void HairDensityPass::executeVisibility(const vk::raii::CommandBuffer& commands) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *visibility_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *visibility_.layout, 0, {*visibilitySet_}, {});
  commands.pushConstants<VisibilityConstants>(*visibility_.layout, vk::ShaderStageFlagBits::eCompute, 0,
                                              VisibilityConstants{.voxels = glm::uvec4(voxels_, kMarchVoxels)});
  const std::uint32_t groups = kResolution / kVisibilityWorkgroup;
  commands.dispatch(groups, groups, groups);
}

void HairDensityPass::record(const vk::raii::CommandBuffer& commands) const {
  FrameGraph graph;
  graph.addPass(
      PassName::kHairDensity, [this](FrameGraph::Builder& pass) { declareClear(pass); },
      [this](const vk::raii::CommandBuffer& c) { executeClear(c); });
  graph.addPass(
      PassName::kHairDensity, [this](FrameGraph::Builder& pass) { declareSplat(pass); },
      [this](const vk::raii::CommandBuffer& c) { executeSplat(c); });
  graph.addPass(
      PassName::kHairDensity, [this](FrameGraph::Builder& pass) { declareVisibility(pass); },
      [this](const vk::raii::CommandBuffer& c) { executeVisibility(c); });
  using Stage = vk::PipelineStageFlagBits2;
  graph.leaveAs(occlusion_, ResourceUse::sampled(Stage::eComputeShader | Stage::eFragmentShader));
  graph.leaveAs(density_, ResourceUse::transferSource());
  graph.compile();
  graph.execute(commands);
}

void HairDensityPass::declareReads(FrameGraph::Builder& pass, vk::PipelineStageFlags2 stages) const {
  pass.read(occlusion_, ResourceUse::sampled(stages));
}

}  // namespace mane::render
