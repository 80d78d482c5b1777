#include "render/passes/ocean_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/matrix.hpp>

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

constexpr std::size_t kMaxWaves = 64;  // shaders/ocean_uniforms.glsl

// Mirrors shaders/ocean_uniforms.glsl (std430, vectors of four floats only).
struct OceanUniforms {
  glm::mat4 clipToWorld{1.0f};
  glm::vec4 eye{0.0f};
  glm::vec4 shape{0.0f};
  std::array<glm::vec4, kMaxWaves> waves{};
  std::array<glm::vec4, kMaxWaves / 4> phases{};
  glm::vec4 water{0.0f};
  glm::vec4 sky{0.0f};
  glm::vec4 fog{0.0f};
  glm::vec4 foam{0.0f};
  glm::vec4 foamMap{0.0f};
  glm::vec4 foamStep{0.0f};
  glm::vec4 reachOfWaves{0.0f};
  std::array<glm::vec4, kMaxFoamSources> foamSources{};
  glm::mat4 reflectorFromWorld{1.0f};
  glm::vec4 reflector{0.0f};  // rgb albedo, a: 1 where there is one
  glm::vec4 gridRows{0.0f};   // x: the first row this frame holds; y: how many
};

constexpr std::uint32_t kFoamWorkgroup = 8;                         // shaders/ocean_foam.comp
constexpr std::uint32_t kFoamRun = 8;  // texels an invocation updates, kJacobianRun in shaders/ocean_waves.glsl
constexpr std::uint32_t kGridWorkgroup = 64;                        // shaders/ocean_grid.comp
constexpr vk::DeviceSize kGridVertexBytes = 3 * sizeof(glm::vec4);  // shaders/ocean_grid.glsl

std::uint32_t gridVertices(glm::uvec2 cells) {
  return (cells.x + 1) * (cells.y + 1);
}
constexpr std::uint32_t kProbeWorkgroup = 64;  // shaders/ocean_probe.comp

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool colour(const glm::vec3& v) {
  return finite(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f;
}

Result<void> validate(const OceanData& ocean) {
  const auto bad = [](const std::string& field, const char* expected) {
    return fail("ocean: " + field + " must be " + expected + ".");
  };
  if (ocean.waves.empty() || ocean.waves.size() > kMaxWaves) return bad("waves", "1 to 64 waves");
  for (std::size_t i = 0; i < ocean.waves.size(); ++i) {
    const glm::vec4 w = ocean.waves[i];
    const std::string name = "wave " + std::to_string(i);
    if (!(finite(glm::vec3(w)) && std::isfinite(w.w))) return bad(name, "finite");
    if (std::abs(w.x * w.x + w.y * w.y - 1.0f) > 1e-3f) return bad(name + "'s direction", "unit");
    if (!(w.z > 0.0f)) return bad(name + "'s wavenumber", "positive");
    if (!(w.w >= 0.0f)) return bad(name + "'s amplitude", "≥ 0");
  }
  if (!(std::isfinite(ocean.choppiness) && ocean.choppiness >= 0.0f)) return bad("choppiness", "finite and ≥ 0");
  if (ocean.grid.x < 1 || ocean.grid.y < 1 || ocean.grid.x > 1024 || ocean.grid.y > 1024)
    return bad("grid", "1 to 1024 cells each way");
  if (!(std::isfinite(ocean.reach) && ocean.reach > 0.0f)) return bad("reach", "positive");
  if (!colour(ocean.waterColor)) return bad("waterColor", "finite and ≥ 0");
  if (!(ocean.fresnelPower >= 1.0f && ocean.fresnelPower <= 5.0f)) return bad("fresnelPower", "in [1, 5]");
  if (!colour(ocean.skyColor)) return bad("skyColor", "finite and ≥ 0");
  if (!colour(ocean.fogColor)) return bad("fogColor", "finite and ≥ 0");
  if (!(std::isfinite(ocean.fogDensity) && ocean.fogDensity >= 0.0f)) return bad("fogDensity", "finite and ≥ 0");
  if (!colour(ocean.foamColor)) return bad("foamColor", "finite and ≥ 0");
  if (!std::isfinite(ocean.foamThreshold)) return bad("foamThreshold", "finite");
  if (!(std::isfinite(ocean.foamHalfLife) && ocean.foamHalfLife > 0.0f)) return bad("foamHalfLife", "positive");
  if (!(std::isfinite(ocean.foamGrowth) && ocean.foamGrowth >= 0.0f)) return bad("foamGrowth", "finite and ≥ 0");
  if (!(std::isfinite(ocean.foamCenter.x) && std::isfinite(ocean.foamCenter.y))) return bad("foamCenter", "finite");
  if (!(std::isfinite(ocean.foamExtent) && ocean.foamExtent > 0.0f)) return bad("foamExtent", "positive");
  if (ocean.foamResolution < 1 || ocean.foamResolution > 4096) return bad("foamResolution", "1 to 4096 texels");
  return {};
}

// Two triangles per cell of a (columns + 1) × (rows + 1) vertex grid, row by row.
std::vector<std::uint32_t> gridTriangles(glm::uvec2 cells) {
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(cells.x) * cells.y * 6);
  const std::uint32_t across = cells.x + 1;
  for (std::uint32_t y = 0; y < cells.y; ++y) {
    for (std::uint32_t x = 0; x < cells.x; ++x) {
      const std::uint32_t corner = y * across + x;
      for (std::uint32_t i : {corner, corner + 1, corner + across, corner + 1, corner + across + 1, corner + across})
        indices.push_back(i);
    }
  }
  return indices;
}

// Whether the eye ray through `ndc` meets the sea at rest (y = 0) within `reach` of the eye, as
// shaders/ocean_grid.comp's restPoint() finds it.
bool meetsTheSeaWithinReach(const glm::mat4& clipToWorld, glm::vec3 eye, float reach, glm::vec2 ndc) {
  const glm::vec4 near = clipToWorld * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 far = clipToWorld * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 direction = glm::vec3(far) / far.w - glm::vec3(near) / near.w;
  return direction.y < 0.0f && eye.y * glm::length(glm::vec2(direction.x, direction.z)) < -direction.y * reach;
}

void writeUniforms(const Buffer& buffer, const OceanUniforms& uniforms) {
  std::memcpy(buffer.mapped().data(), &uniforms, sizeof(uniforms));
}

OceanUniforms staticUniforms(const OceanData& ocean) {
  OceanUniforms u;
  u.shape = {ocean.choppiness, float(ocean.waves.size()), float(ocean.grid.x), float(ocean.grid.y)};
  for (std::size_t i = 0; i < ocean.waves.size(); ++i) u.waves[i] = ocean.waves[i];
  u.water = glm::vec4(ocean.waterColor, ocean.fresnelPower);
  u.sky = glm::vec4(ocean.skyColor, 0.0f);
  u.fog = glm::vec4(ocean.fogColor, ocean.fogDensity);
  u.foam = glm::vec4(ocean.foamColor, ocean.foamThreshold);
  const glm::vec2 corner = ocean.foamCenter - 0.5f * ocean.foamExtent;
  u.foamMap = {corner.x, corner.y, 1.0f / ocean.foamExtent, float(ocean.foamResolution)};
  u.foamStep = {1.0f, 0.0f, 0.0f, 0.0f};
  float amplitudes = 0.0f;
  for (const glm::vec4& wave : ocean.waves) amplitudes += wave.w;
  u.reachOfWaves = {ocean.choppiness * amplitudes, 0.0f, 0.0f, 0.0f};
  return u;
}

}  // namespace

// Below a plane the horizon is a line on the screen, so the rows it crosses are found at the
// overhang's left and right edges.
GridRows oceanGridRows(const glm::mat4& clipToWorld, glm::vec3 eye, float reach, glm::uvec2 cells) {
  const GridRows every{0, cells.y};
  if (!(eye.y > 0.0f)) return every;
  const float step = 2.0f * kOceanGridOverhang / float(cells.y);
  std::uint32_t lowest = cells.y;
  std::uint32_t highest = 0;
  for (std::uint32_t row = 0; row <= cells.y; ++row) {
    const float y = -kOceanGridOverhang + float(row) * step;
    if (meetsTheSeaWithinReach(clipToWorld, eye, reach, {-kOceanGridOverhang, y}) ||
        meetsTheSeaWithinReach(clipToWorld, eye, reach, {kOceanGridOverhang, y})) {
      lowest = std::min(lowest, row);
      highest = std::max(highest, row);
    }
  }
  if (lowest > highest) return every;
  const std::uint32_t first = lowest > 0 ? lowest - 1 : 0;
  const std::uint32_t last = std::min(highest + 1, cells.y);
  return {first, std::max(last - first, 1u)};
}

OceanPass::OceanPass(const Device& device, const OceanData& ocean) : device_(&device), data_(ocean) {}

Result<std::unique_ptr<OceanPass>> OceanPass::create(const Device& device, const OceanData& ocean) {
  if (auto valid = validate(ocean); !valid) return std::unexpected(valid.error());
  std::unique_ptr<OceanPass> pass(new OceanPass(device, ocean));
  try {
    using Type = vk::DescriptorType;
    using Stage = vk::ShaderStageFlagBits;
    using Usage = vk::ImageUsageFlagBits;
    pass->uniforms_ = Buffer(device, sizeof(OceanUniforms), vk::BufferUsageFlagBits::eStorageBuffer,
                             vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    writeUniforms(pass->uniforms_, staticUniforms(ocean));
    const std::vector<std::uint32_t> indices = gridTriangles(ocean.grid);
    pass->indices_ = Buffer::withData(device, std::as_bytes(std::span(indices)), vk::BufferUsageFlagBits::eIndexBuffer);
    pass->grid_ = Buffer(device, gridVertices(ocean.grid) * kGridVertexBytes, vk::BufferUsageFlagBits::eStorageBuffer,
                         vk::MemoryPropertyFlagBits::eDeviceLocal);

    const std::uint32_t side = ocean.foamResolution;
    pass->foam_ =
        Image(device, {.extent = {side, side},
                       .format = vk::Format::eR32Sfloat,
                       .usage = Usage::eStorage | Usage::eSampled | Usage::eTransferDst | Usage::eTransferSrc});
    device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      using Stage2 = vk::PipelineStageFlagBits2;
      using Access = vk::AccessFlagBits2;
      using Layout = vk::ImageLayout;
      transition(commands, pass->foam_, Layout::eUndefined, Layout::eTransferDstOptimal, Stage2::eNone, {},
                 Stage2::eClear, Access::eTransferWrite);
      commands.clearColorImage(*pass->foam_.image(), Layout::eTransferDstOptimal,
                               vk::ClearColorValue(std::array{0.0f, 0.0f, 0.0f, 0.0f}),
                               vk::ImageSubresourceRange{vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1});
      transition(commands, pass->foam_, Layout::eTransferDstOptimal, Layout::eGeneral, Stage2::eClear,
                 Access::eTransferWrite, Stage2::eAllCommands, Access::eShaderStorageRead);
    });
    pass->foamSampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);

    const auto vertexAndFragment = vk::ShaderStageFlags(Stage::eVertex | Stage::eFragment);
    const auto compute = vk::ShaderStageFlags(Stage::eCompute);
    pass->drawLayout_ = makeSetLayout(device, {{Type::eStorageBuffer, vertexAndFragment},
                                               {Type::eCombinedImageSampler, vk::ShaderStageFlags(Stage::eFragment)},
                                               {Type::eStorageBuffer, vk::ShaderStageFlags(Stage::eVertex)}});
    pass->foamLayout_ = makeSetLayout(device, {{Type::eStorageBuffer, compute}, {Type::eStorageImage, compute}});
    pass->gridLayout_ = makeSetLayout(device, {{Type::eStorageBuffer, compute}, {Type::eStorageBuffer, compute}});
    pass->pool_ = makeDescriptorPool(
        device, 3, {{Type::eCombinedImageSampler, 1}, {Type::eStorageImage, 1}, {Type::eStorageBuffer, 5}});
    pass->drawSet_ = allocateSet(device, pass->pool_, pass->drawLayout_);
    pass->foamSet_ = allocateSet(device, pass->pool_, pass->foamLayout_);
    pass->gridSet_ = allocateSet(device, pass->pool_, pass->gridLayout_);
    writeStorageBuffer(device, pass->drawSet_, 0, pass->uniforms_);
    writeSampledImage(device, pass->drawSet_, 1, pass->foam_.view(), pass->foamSampler_);
    writeStorageBuffer(device, pass->drawSet_, 2, pass->grid_);
    writeStorageBuffer(device, pass->foamSet_, 0, pass->uniforms_);
    writeStorageImage(device, pass->foamSet_, 1, pass->foam_.view());
    writeStorageBuffer(device, pass->gridSet_, 0, pass->uniforms_);
    writeStorageBuffer(device, pass->gridSet_, 1, pass->grid_);

    pass->foamPipeline_ = makeComputePipeline(device, "ocean_foam.comp", pass->foamLayout_);
    pass->gridPipeline_ = makeComputePipeline(device, "ocean_grid.comp", pass->gridLayout_);
  } catch (const std::exception& error) {
    return fail(std::string("ocean: creating its GPU objects failed: ") + error.what());
  }
  return pass;
}

Result<void> OceanPass::buildDrawPipeline(const Formats& formats, vk::DescriptorSetLayout frameLayout) {
  try {
    const bool depth = formats.depth != vk::Format::eUndefined;
    drawPipeline_ = makeGraphicsPipeline(*device_, GraphicsPipelineSettings{.vertexShader = "ocean.vert",
                                                                            .fragmentShader = "ocean.frag",
                                                                            .colorFormats = {formats.color},
                                                                            .depthFormat = formats.depth,
                                                                            .depthTest = depth,
                                                                            .depthWrite = depth,
                                                                            .samples = formats.samples,
                                                                            .setLayouts = {frameLayout, *drawLayout_}});
  } catch (const std::exception& error) {
    return fail(std::string("ocean: creating its pipeline failed: ") + error.what());
  }
  return {};
}

Result<void> OceanPass::prepare(const FrameInput& frame, float aspect) {
  if (!frame.ocean || frame.ocean->phases.size() != data_.waves.size())
    return fail("ocean: the frame gives " + std::to_string(frame.ocean ? frame.ocean->phases.size() : 0) +
                " wave phases for the scene's " + std::to_string(data_.waves.size()) + " waves.");
  if (!(std::isfinite(frame.ocean->seconds) && frame.ocean->seconds >= 0.0f))
    return fail("ocean: the frame's time step must be finite and ≥ 0.");
  OceanUniforms u = staticUniforms(data_);
  u.clipToWorld = glm::inverse(frame.camera.projection(aspect) * frame.camera.view());
  u.eye = glm::vec4(frame.camera.position, data_.reach);
  rows_ = oceanGridRows(u.clipToWorld, frame.camera.position, data_.reach, data_.grid);
  u.gridRows = {float(rows_.first), float(rows_.count), 0.0f, 0.0f};
  for (std::size_t i = 0; i < data_.waves.size(); ++i) u.phases[i / 4][int(i % 4)] = frame.ocean->phases[i];
  const std::vector<glm::vec4>& sources = frame.ocean->foamSources;
  if (sources.size() > kMaxFoamSources)
    return fail("ocean: the frame lays foam from " + std::to_string(sources.size()) + " sources, more than " +
                std::to_string(kMaxFoamSources) + ".");
  const double seconds = frame.ocean->seconds;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const glm::vec4 s = sources[i];
    if (!(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z) && s.z > 0.0f && std::isfinite(s.w) &&
          s.w >= 0.0f))
      return fail("ocean: foam source " + std::to_string(i) +
                  " must have a finite place, a radius > 0 and a rate ≥ 0.");
    u.foamSources[i] = {s.x, s.y, 1.0f / (s.z * s.z), float(s.w * seconds)};
  }
  if (const std::optional<OceanReflector>& reflector = frame.ocean->reflector) {
    const glm::mat4 inverse = glm::inverse(reflector->worldFromUnitSphere);
    bool finiteMatrix = true;
    for (int column = 0; column < 4; ++column)
      finiteMatrix = finiteMatrix && finite(glm::vec3(inverse[column])) && std::isfinite(inverse[column].w);
    if (!finiteMatrix) return fail("ocean: the reflector's matrix must be invertible.");
    if (!colour(reflector->albedo)) return fail("ocean: the reflector's albedo must be finite and ≥ 0.");
    u.reflectorFromWorld = inverse;
    u.reflector = glm::vec4(reflector->albedo, 1.0f);
  }
  u.foamStep = {float(std::exp2(-seconds / data_.foamHalfLife)), float(data_.foamGrowth * seconds),
                float(sources.size()), 0.0f};
  writeUniforms(uniforms_, u);
  return {};
}

void OceanPass::declareGrid(FrameGraph::Builder& pass) const {
  pass.write(grid_, ResourceUse::storageWrite(vk::PipelineStageFlagBits2::eComputeShader), Contents::kDiscard);
}

void OceanPass::recordGrid(const vk::raii::CommandBuffer& commands) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *gridPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *gridPipeline_.layout, 0, {*gridSet_}, {});
  commands.dispatch((gridVertices({data_.grid.x, rows_.count}) + kGridWorkgroup - 1) / kGridWorkgroup, 1, 1);
}

void OceanPass::declareFoam(FrameGraph::Builder& pass) const {
  pass.write(foam_, ResourceUse::storageReadWrite(vk::PipelineStageFlagBits2::eComputeShader));
}

void OceanPass::recordFoam(const vk::raii::CommandBuffer& commands) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *foamPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *foamPipeline_.layout, 0, {*foamSet_}, {});
  const std::uint32_t rows = (data_.foamResolution + kFoamWorkgroup - 1) / kFoamWorkgroup;
  const std::uint32_t runs = kFoamWorkgroup * kFoamRun;
  commands.dispatch((data_.foamResolution + runs - 1) / runs, rows, 1);
}

void OceanPass::declareDrawReads(FrameGraph::Builder& pass) const {
  pass.read(grid_, ResourceUse::storageRead(vk::PipelineStageFlagBits2::eVertexShader));
  pass.read(foam_, ResourceUse::sampled(vk::PipelineStageFlagBits2::eFragmentShader));
}

void OceanPass::leaveFoam(FrameGraph& graph) const {
  graph.leaveAs(foam_, ResourceUse::storageReadWrite(vk::PipelineStageFlagBits2::eComputeShader));
}

void OceanPass::draw(const vk::raii::CommandBuffer& commands, const vk::raii::DescriptorSet& frameSet,
                     vk::Extent2D extent) const {
  setViewportAndScissor(commands, extent);
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *drawPipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *drawPipeline_.layout, 0, {*frameSet, *drawSet_}, {});
  commands.bindIndexBuffer(*indices_.buffer(), 0, vk::IndexType::eUint32);
  // The index buffer lists the cells row by row, so the window's rows are its first ones.
  commands.drawIndexed(6 * data_.grid.x * rows_.count, 1, 0, 0, 0);
}

std::vector<OceanProbeSample> OceanPass::probe(std::span<const glm::vec2> rests) const {
  using Type = vk::DescriptorType;
  const Device& device = *device_;
  const auto compute = vk::ShaderStageFlags(vk::ShaderStageFlagBits::eCompute);
  const auto storage = vk::BufferUsageFlagBits::eStorageBuffer;
  const auto host = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
  Buffer points(device, rests.size_bytes(), storage, host);
  std::memcpy(points.mapped().data(), rests.data(), rests.size_bytes());
  Buffer samples(device, rests.size() * 2 * sizeof(glm::vec4), storage, host);
  const auto layout = makeSetLayout(
      device, {{Type::eStorageBuffer, compute}, {Type::eStorageBuffer, compute}, {Type::eStorageBuffer, compute}});
  const auto pool = makeDescriptorPool(device, 1, {{Type::eStorageBuffer, 3}});
  const auto set = allocateSet(device, pool, layout);
  writeStorageBuffer(device, set, 0, uniforms_);
  writeStorageBuffer(device, set, 1, points);
  writeStorageBuffer(device, set, 2, samples);
  const Pipeline pipeline = makeComputePipeline(device, "ocean_probe.comp", layout, sizeof(std::uint32_t));
  const auto count = std::uint32_t(rests.size());
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
    commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, {*set}, {});
    commands.pushConstants<std::uint32_t>(*pipeline.layout, vk::ShaderStageFlagBits::eCompute, 0, count);
    commands.dispatch((count + kProbeWorkgroup - 1) / kProbeWorkgroup, 1, 1);
    const vk::MemoryBarrier2 barrier{.srcStageMask = vk::PipelineStageFlagBits2::eComputeShader,
                                     .srcAccessMask = vk::AccessFlagBits2::eShaderStorageWrite,
                                     .dstStageMask = vk::PipelineStageFlagBits2::eHost,
                                     .dstAccessMask = vk::AccessFlagBits2::eHostRead};
    commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &barrier});
  });
  std::vector<OceanProbeSample> result(rests.size());
  const auto* values = reinterpret_cast<const glm::vec4*>(samples.mapped().data());
  for (std::size_t i = 0; i < rests.size(); ++i)
    result[i] = {glm::vec3(values[2 * i]), glm::vec3(values[2 * i + 1]), values[2 * i].w};
  return result;
}

std::vector<float> OceanPass::readFoam() const {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  using Layout = vk::ImageLayout;
  device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    transition(commands, foam_, Layout::eGeneral, Layout::eTransferSrcOptimal, Stage::eAllCommands,
               Access::eShaderStorageWrite, Stage::eAllTransfer, Access::eTransferRead);
  });
  const std::vector<std::byte> bytes = readBack(*device_, foam_, sizeof(float));
  device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    transition(commands, foam_, Layout::eTransferSrcOptimal, Layout::eGeneral, Stage::eAllTransfer,
               Access::eTransferRead, Stage::eAllCommands, Access::eShaderStorageRead | Access::eShaderStorageWrite);
  });
  std::vector<float> texels(bytes.size() / sizeof(float));
  std::memcpy(texels.data(), bytes.data(), texels.size() * sizeof(float));
  return texels;
}

}  // namespace mane::render
