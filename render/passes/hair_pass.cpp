#include "render/passes/hair_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <string>

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

// std140 mirror of HairUniforms in shaders/hair_uniforms.glsl.
struct HairUniforms {
  glm::mat4 viewProjection;
  glm::vec4 eye;
  glm::vec4 ambient;
  glm::vec4 lightDirection[HairPass::kMaxLights];
  glm::vec4 lightRadiance[HairPass::kMaxLights];
  glm::vec4 groom;
  glm::vec4 viewport;
  glm::uvec4 counts;
};
static_assert(sizeof(HairUniforms) == 64 + 2 * 16 + 2 * 16 * HairPass::kMaxLights + 3 * 16);

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
  return {};
}

}  // namespace

Result<std::unique_ptr<HairPass>> HairPass::create(const Device& device, const MarschnerLut& lut,
                                                   const HairPassSettings& settings) {
  try {
    return std::unique_ptr<HairPass>(new HairPass(device, lut, settings));
  } catch (const vk::SystemError& error) {
    return fail(std::string("hair pass: Vulkan error while creating the pipeline: ") + error.what());
  }
}

HairPass::HairPass(const Device& device, const MarschnerLut& lut, const HairPassSettings& settings) : device_(&device) {
  using Stage = vk::ShaderStageFlagBits;
  using Type = vk::DescriptorType;
  setLayout_ = makeSetLayout(device, {{Type::eUniformBuffer, Stage::eVertex | Stage::eFragment},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eStorageBuffer, Stage::eVertex},
                                      {Type::eCombinedImageSampler, Stage::eFragment},
                                      {Type::eCombinedImageSampler, Stage::eFragment}});
  const bool depth = settings.depthFormat != vk::Format::eUndefined;
  pipeline_ = makeGraphicsPipeline(device, GraphicsPipelineSettings{.vertexShader = "hair.vert",
                                                                    .fragmentShader = "hair.frag",
                                                                    .cullMode = vk::CullModeFlagBits::eNone,
                                                                    .colorFormats = {settings.colorFormat},
                                                                    .blend = Blend::kPremultipliedAlpha,
                                                                    .depthFormat = settings.depthFormat,
                                                                    .depthTest = depth,
                                                                    .depthWrite = false,
                                                                    .samples = settings.samples,
                                                                    .setLayouts = {*setLayout_}});
  pool_ = makeDescriptorPool(device, 1,
                             {{Type::eUniformBuffer, 1}, {Type::eStorageBuffer, 2}, {Type::eCombinedImageSampler, 2}});
  set_ = allocateSet(device, pool_, setLayout_);
  uniforms_ = Buffer(device, sizeof(HairUniforms), vk::BufferUsageFlagBits::eUniformBuffer,
                     vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  writeUniformBuffer(device, set_, 0, uniforms_);

  const std::array images{vk::DescriptorImageInfo{.sampler = *lut.sampler(),
                                                  .imageView = *lut.longitudinalView(),
                                                  .imageLayout = vk::ImageLayout::eShaderReadOnlyOptimal},
                          vk::DescriptorImageInfo{.sampler = *lut.sampler(),
                                                  .imageView = *lut.azimuthalView(),
                                                  .imageLayout = vk::ImageLayout::eShaderReadOnlyOptimal}};
  device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set_,
                                                              .dstBinding = 3,
                                                              .descriptorCount = 1,
                                                              .descriptorType = Type::eCombinedImageSampler,
                                                              .pImageInfo = &images[0]},
                                       {});
  device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set_,
                                                              .dstBinding = 4,
                                                              .descriptorCount = 1,
                                                              .descriptorType = Type::eCombinedImageSampler,
                                                              .pImageInfo = &images[1]},
                                       {});

  // Ambient: La · ∫S dωi, the white-furnace albedo of marschner.hpp, at θr = 0.
  const AzimuthalLobes albedo = azimuthalAlbedo(lut.params(), 1.0);
  ambientAlbedo_ = glm::vec3(albedo.tt + albedo.trt + glm::dvec3(albedo.r));
}

Result<void> HairPass::setStrands(const HairStrands& strands) {
  if (!strands.positions || !strands.tangents) return fail("hair strands: the position or tangent buffer is null");
  if (strands.verticesPerStrand < 2)
    return fail("hair strands: need at least 2 vertices per strand, got " + std::to_string(strands.verticesPerStrand));
  const std::uint64_t vertices = std::uint64_t(strands.strandCount) * (strands.verticesPerStrand - 1) * 6;
  if (vertices > std::numeric_limits<std::uint32_t>::max())
    return fail("hair strands: " + std::to_string(strands.strandCount) + " strands × " +
                std::to_string(strands.verticesPerStrand) + " vertices need " + std::to_string(vertices) +
                " ribbon vertices, more than one draw can count (2^32 − 1)");

  const std::array buffers{vk::DescriptorBufferInfo{.buffer = strands.positions, .offset = 0, .range = VK_WHOLE_SIZE},
                           vk::DescriptorBufferInfo{.buffer = strands.tangents, .offset = 0, .range = VK_WHOLE_SIZE}};
  device_->device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set_,
                                                                .dstBinding = 1,
                                                                .descriptorCount = 2,
                                                                .descriptorType = vk::DescriptorType::eStorageBuffer,
                                                                .pBufferInfo = buffers.data()},
                                         {});
  vertexCount_ = static_cast<std::uint32_t>(vertices);
  verticesPerStrand_ = strands.verticesPerStrand;
  // Keep the uniforms of an earlier update in step (counts.y is Nd).
  std::memcpy(uniforms_.mapped().data() + offsetof(HairUniforms, counts) + sizeof(std::uint32_t), &verticesPerStrand_,
              sizeof(verticesPerStrand_));
  return {};
}

Result<void> HairPass::update(const HairView& view, std::span<const DirectionalLight> lights, glm::vec3 ambient,
                              const HairGroomSettings& groom) {
  if (auto valid = validate(groom); !valid) return valid;
  if (view.extent.width == 0 || view.extent.height == 0) return fail("hair view: the extent is empty");
  const float determinant = glm::determinant(view.viewProjection);
  if (!finite(view.viewProjection) || !std::isfinite(determinant) || determinant == 0.0f)
    return fail("hair view: the view-projection matrix is not finite and invertible");

  HairUniforms uniforms{};
  uniforms.viewProjection = view.viewProjection;
  // The eye is the point (or, orthographic, the point at infinity) that projects to clip
  // (0, 0, 1, 0): the null direction of the projection. Clip z grows away from the eye, so an
  // orthographic eye lies along the negated direction.
  const glm::vec4 eye = glm::inverse(view.viewProjection) * glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
  const float directionScale = glm::length(glm::vec3(eye));
  if (std::abs(eye.w) > 1e-6f * directionScale)
    uniforms.eye = glm::vec4(glm::vec3(eye) / eye.w, 1.0f);
  else
    uniforms.eye = glm::vec4(-glm::vec3(eye) / directionScale, 0.0f);
  uniforms.ambient = glm::vec4(ambient * ambientAlbedo_, 0.0f);
  const std::size_t count = std::min(lights.size(), kMaxLights);
  for (std::size_t i = 0; i < count; ++i) {
    uniforms.lightDirection[i] = glm::vec4(glm::normalize(lights[i].direction), 0.0f);
    uniforms.lightRadiance[i] = glm::vec4(lights[i].color * lights[i].intensity, 0.0f);
  }
  uniforms.groom = glm::vec4(groom.width, groom.tipWidthScale, groom.opacity, groom.minimumPixelWidth);
  uniforms.viewport = glm::vec4(float(view.extent.width), float(view.extent.height), 0.0f, 0.0f);
  uniforms.counts = glm::uvec4(static_cast<std::uint32_t>(count), verticesPerStrand_, 0u, 0u);
  std::memcpy(uniforms_.mapped().data(), &uniforms, sizeof(uniforms));
  extent_ = view.extent;
  return {};
}

Result<void> HairPass::update(const FrameInput& frame, vk::Extent2D extent, const HairGroomSettings& groom) {
  if (extent.width == 0 || extent.height == 0) return fail("hair view: the extent is empty");
  const float aspect = float(extent.width) / float(extent.height);
  return update(HairView{frame.camera.projection(aspect) * frame.camera.view(), extent}, frame.lights, frame.ambient,
                groom);
}

void HairPass::draw(const vk::raii::CommandBuffer& commands) const {
  if (vertexCount_ == 0 || extent_.width == 0) return;
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline_.layout, 0, {*set_}, {});
  setViewportAndScissor(commands, extent_);
  commands.draw(vertexCount_, 1, 0, 0);
}

}  // namespace mane::render
