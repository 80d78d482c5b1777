#include "render/passes/hair_lighting_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "render/descriptors.hpp"
#include "render/strand_looks.hpp"

namespace mane::render {
namespace {

constexpr std::uint32_t kFirstShadowBinding = 6;

// Read by shaders/hair_lighting.comp as a texel buffer, vec4 k as texel k (its k*Texel constants).
struct LightingUniforms {
  glm::vec4 eye;
  glm::vec4 ambient;
  glm::vec4 lightDirection[HairLightingPass::kMaxLights];
  glm::vec4 lightRadiance[HairLightingPass::kMaxLights];
  glm::uvec4 counts;  // x: lights, y: vertices per strand, z: 1 where the environment lights the hair
  HairShadowUniforms shadows;
  glm::vec4 environment[9];  // rgb: the environment's radiance as harmonics
  HairLightingPass::EnvironmentBands environmentBands;
  HairVisibilityPlacement hairVisibility;  // w = 0: no occlusion volume this frame
};
static_assert(sizeof(LightingUniforms) == 3 * 16 + 2 * 16 * HairLightingPass::kMaxLights + sizeof(HairShadowUniforms) +
                                              (9 + 3 * kHairEnvironmentSamples + 2) * 16);
constexpr std::uint32_t kHairVisibilityBinding = 16;

}  // namespace

glm::vec4 hairEye(const glm::mat4& viewProjection) {
  // The eye is the point (or, orthographic, the point at infinity) that projects to clip
  // (0, 0, 1, 0): the null direction of the projection. Clip z grows away from the eye, so an
  // orthographic eye lies along the negated direction.
  const glm::vec4 eye = glm::inverse(viewProjection) * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
  const float directionScale = glm::length(glm::vec3(eye));
  if (std::abs(eye.w) > 1e-6f * directionScale) return glm::vec4(glm::vec3(eye) / eye.w, 1.0f);
  return glm::vec4(-glm::vec3(eye) / directionScale, 0.0f);
}

Result<std::unique_ptr<HairLightingPass>> HairLightingPass::create(const Device& device, const MarschnerLut& lut,
                                                                   const HairShadowPass& shadows,
                                                                   const Buffer& positions, const Buffer& tangents,
                                                                   std::uint32_t strandCount,
                                                                   std::uint32_t verticesPerStrand) {
  if (strandCount == 0 || verticesPerStrand < 2)
    return fail("hair lighting: need at least one strand of 2 or more vertices, got " + std::to_string(strandCount) +
                " strands of " + std::to_string(verticesPerStrand));
  const std::uint64_t vertices = std::uint64_t(strandCount) * verticesPerStrand;
  const std::uint64_t bytes = vertices * sizeof(glm::vec4);
  if (positions.size() < bytes || tangents.size() < bytes)
    return fail("hair lighting: " + std::to_string(vertices) + " vertices need " + std::to_string(bytes) +
                " bytes of positions and of tangents; the buffers hold " + std::to_string(positions.size()) + " and " +
                std::to_string(tangents.size()));
  // The shade list is read as texels too: its 4-word header, then a word per vertex.
  if (bytes > device.limits().maxStorageBufferRange || vertices + 4 > device.limits().maxTexelBufferElements ||
      (vertices + kWorkgroupSize - 1) / kWorkgroupSize > device.limits().maxComputeWorkGroupCount[0])
    return fail("hair lighting: " + std::to_string(vertices) +
                " vertices exceed the device's storage or texel buffer range or dispatch size");
  try {
    return std::unique_ptr<HairLightingPass>(new HairLightingPass(
        device, lut, shadows, positions, tangents, static_cast<std::uint32_t>(vertices), verticesPerStrand));
  } catch (const vk::SystemError& error) {
    return fail(std::string("hair lighting: Vulkan error while creating the pass: ") + error.what());
  }
}

HairLightingPass::HairLightingPass(const Device& device, const MarschnerLut& lut, const HairShadowPass& shadows,
                                   const Buffer& positions, const Buffer& tangents, std::uint32_t vertexCount,
                                   std::uint32_t verticesPerStrand)
    : device_(&device),
      shadows_(&shadows),
      positions_(&positions),
      tangents_(&tangents),
      verticesPerStrand_(verticesPerStrand) {
  using Type = vk::DescriptorType;
  const auto compute = vk::ShaderStageFlags(vk::ShaderStageFlagBits::eCompute);
  const std::pair sampler{Type::eCombinedImageSampler, compute};
  setLayout_ = makeSetLayout(device, {{Type::eUniformTexelBuffer, compute},  // the uniforms: see the shader
                                      {Type::eUniformTexelBuffer, compute},
                                      {Type::eUniformTexelBuffer, compute},
                                      {Type::eStorageBuffer, compute},
                                      sampler,
                                      sampler,  // the LUTs
                                      sampler,
                                      sampler,
                                      sampler,
                                      sampler,  // shadow opacity, 4 slots
                                      sampler,
                                      sampler,
                                      sampler,
                                      sampler,                               // shadow first depth, 4 slots
                                      {Type::eUniformTexelBuffer, compute},  // the shade list
                                      {Type::eUniformTexelBuffer, compute},  // the strands' looks
                                      sampler});                             // the hair's occlusion volume
  pipeline_ = makeComputePipeline(device, "hair_lighting.comp", setLayout_, 0, shadows.shaderConstants());
  pool_ = makeDescriptorPool(device, 1,
                             {{Type::eStorageBuffer, 1},
                              {Type::eUniformTexelBuffer, 5},
                              {Type::eCombinedImageSampler, 3 + HairShadowPass::kBindings}});
  set_ = allocateSet(device, pool_, setLayout_);

  uniforms_ = Buffer(device, sizeof(LightingUniforms), vk::BufferUsageFlagBits::eUniformTexelBuffer,
                     vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  radiance_ = Buffer(device, vk::DeviceSize(vertexCount) * sizeof(glm::vec4),
                     vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eVertexBuffer |
                         vk::BufferUsageFlagBits::eTransferSrc,
                     vk::MemoryPropertyFlagBits::eDeviceLocal);
  std::memset(uniforms_.mapped().data(), 0, sizeof(LightingUniforms));
  // Words, not floats, so the counts pass unchanged; the shader casts the rest back to floats.
  uniformTexels_ = makeTexelView(device, *uniforms_.buffer(), vk::Format::eR32G32B32A32Uint);
  writeUniformTexelBuffer(device, set_, 0, uniformTexels_);
  positionTexels_ = makeTexelView(device, *positions.buffer(), vk::Format::eR32G32B32A32Sfloat);
  tangentTexels_ = makeTexelView(device, *tangents.buffer(), vk::Format::eR32G32B32A32Sfloat);
  writeUniformTexelBuffer(device, set_, 1, positionTexels_);
  writeUniformTexelBuffer(device, set_, 2, tangentTexels_);
  writeStorageBuffer(device, set_, 3, radiance_);
  everyVertex_ = everyVertex(device, vertexCount);
  setShadeList(everyVertex_);
  everyStrandPlain_ = uploadStrandLooks(device, {}, vertexCount / verticesPerStrand);
  bindStrandLooks(everyStrandPlain_);
  writeSampledImage(device, set_, 4, lut.longitudinalView(), lut.sampler());
  writeSampledImage(device, set_, 5, lut.azimuthalView(), lut.sampler());
  refreshShadows();
  noHairVisibility_ = clearedVisibilityVolume(device, 1);
  hairVisibilitySampler_ = makeVisibilitySampler(device);
  setHairVisibility(nullptr);

  // Ambient: La · ∫S dωi, the white-furnace albedo of marschner.hpp, at θr = 0.
  const AzimuthalLobes albedo = azimuthalAlbedo(lut.params(), 1.0);
  ambientAlbedo_ = glm::vec3(albedo.tt + albedo.trt + glm::dvec3(albedo.r));
  params_ = lut.params();
}

void HairLightingPass::setEnvironment(const std::optional<SphericalHarmonics9>& irradianceOverPi) {
  environment_ = irradianceOverPi;
  if (!environment_ || environmentBands_) return;
  const std::vector<HairEnvironmentBands> table = hairEnvironmentTable(params_);
  EnvironmentBands& bands = environmentBands_.emplace();
  for (std::size_t k = 0; k < kHairEnvironmentSamples; ++k)
    for (std::size_t l = 0; l < 3; ++l)
      bands[3 * k + l] = glm::vec4(glm::vec3(table[k].crossed[l]), float(table[k].reflected[l]));
}

void HairLightingPass::setHairVisibility(const HairDensityPass* visibility) {
  hairVisibility_ = visibility;
  writeSampledImage(*device_, set_, kHairVisibilityBinding,
                    visibility ? visibility->occlusion().view() : noHairVisibility_.view(),
                    visibility ? visibility->sampler() : hairVisibilitySampler_);
}

void HairLightingPass::setShadeList(const Buffer& shadeList) {
  shadeListTexels_ = makeTexelView(*device_, *shadeList.buffer(), vk::Format::eR32Uint);
  writeUniformTexelBuffer(*device_, set_, 14, shadeListTexels_);
  shadeList_ = &shadeList;
}

Result<void> HairLightingPass::setStrandLooks(const Buffer& looks) {
  const auto strands = static_cast<std::uint32_t>(radiance_.size() / sizeof(glm::vec4) / verticesPerStrand_);
  const vk::DeviceSize needed = vk::DeviceSize(strands) * sizeof(HairStrandLook);
  if (looks.size() < needed)
    return fail("hair lighting: " + std::to_string(strands) + " strands need " + std::to_string(needed) +
                " bytes of looks, the buffer holds " + std::to_string(looks.size()));
  bindStrandLooks(looks);
  return {};
}

void HairLightingPass::bindStrandLooks(const Buffer& looks) {
  // Written once when uploaded and only read since: no frame graph needs to order it.
  strandLookTexels_ = makeTexelView(*device_, *looks.buffer(), vk::Format::eR32G32B32A32Sfloat);
  writeUniformTexelBuffer(*device_, set_, 15, strandLookTexels_);
}

Buffer HairLightingPass::everyVertex(const Device& device, std::uint32_t vertices) {
  std::vector<std::uint32_t> list{(vertices + kWorkgroupSize - 1) / kWorkgroupSize, 1, 1, vertices};
  for (std::uint32_t v = 0; v < vertices; ++v) list.push_back(v);
  return Buffer::withData(device, std::as_bytes(std::span(list)),
                          vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eIndirectBuffer |
                              vk::BufferUsageFlagBits::eUniformTexelBuffer);
}

void HairLightingPass::refreshShadows() {
  shadows_->writeDescriptors(set_, kFirstShadowBinding);
}

Result<void> HairLightingPass::update(const glm::mat4& viewProjection, std::span<const DirectionalLight> lights,
                                      glm::vec3 ambient, const HairShadowUniforms& shadows) {
  LightingUniforms uniforms{};
  const std::size_t count = std::min(lights.size(), kMaxLights);
  for (std::size_t i = 0; i < count; ++i) {
    const float length = glm::length(lights[i].direction);
    if (!(std::isfinite(length) && length > 0.0f))
      return fail("hair lighting: light " + std::to_string(i) + "'s direction is not finite and non-zero");
    uniforms.lightDirection[i] = glm::vec4(lights[i].direction / length, 0.0f);
    uniforms.lightRadiance[i] = glm::vec4(lights[i].color * lights[i].intensity, 0.0f);
  }
  uniforms.eye = hairEye(viewProjection);
  uniforms.ambient = glm::vec4(ambient * ambientAlbedo_, 0.0f);
  uniforms.counts = glm::uvec4(static_cast<std::uint32_t>(count), verticesPerStrand_, environment_ ? 1u : 0u, 0u);
  uniforms.shadows = shadows;
  if (environment_) {
    // The radiance's harmonics: the irradiance's over π with the clamped cosine's band factors
    // (1, 2/3, 1/4) undone.
    constexpr std::array<float, 9> kUnconvolve{1.0f, 1.5f, 1.5f, 1.5f, 4.0f, 4.0f, 4.0f, 4.0f, 4.0f};
    for (std::size_t i = 0; i < 9; ++i) uniforms.environment[i] = glm::vec4((*environment_)[i] * kUnconvolve[i], 0.0f);
    uniforms.environmentBands = *environmentBands_;
    if (hairVisibility_) uniforms.hairVisibility = hairVisibility_->placement();
  }
  std::memcpy(uniforms_.mapped().data(), &uniforms, sizeof(uniforms));
  return {};
}

void HairLightingPass::declare(FrameGraph::Builder& pass) const {
  using Stage = vk::PipelineStageFlagBits2;
  const auto compute = Stage::eComputeShader;
  pass.read(*positions_, ResourceUse::sampled(compute));  // texel buffers
  pass.read(*tangents_, ResourceUse::sampled(compute));
  pass.read(*shadeList_, ResourceUse::sampled(compute));
  pass.read(*shadeList_, ResourceUse::indirectCommands());  // the dispatch's size
  shadows_->declareReads(pass, compute);
  if (hairVisibility_) hairVisibility_->declareReads(pass, compute);
  pass.write(radiance_, ResourceUse::storageWrite(compute));
}

void HairLightingPass::execute(const vk::raii::CommandBuffer& commands) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.layout, 0, {*set_}, {});
  commands.dispatchIndirect(*shadeList_->buffer(), 0);
}

void HairLightingPass::record(const vk::raii::CommandBuffer& commands) const {
  using Stage = vk::PipelineStageFlagBits2;
  using Access = vk::AccessFlagBits2;
  const ResourceUse readers{Stage::eVertexShader | Stage::eVertexAttributeInput | Stage::eCopy,
                            Access::eShaderStorageRead | Access::eVertexAttributeRead | Access::eTransferRead};
  FrameGraph::recordAlone(commands, PassName::kHairLighting, *this, {{radiance_, readers}});
}

}  // namespace mane::render
