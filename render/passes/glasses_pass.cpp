#include "render/passes/glasses_pass.hpp"

#include <cstring>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

// Push constants of shaders/glasses_lens.glsl.
struct LensConstants {
  glm::mat4 model;
  glm::vec4 surfaces;
  glm::vec4 outline;
  glm::vec4 transmittance;
};

// std140 mirror of GlassesView in shaders/glasses_refraction.glsl.
struct GlassesView {
  glm::mat4 clipToWorld;
  glm::vec4 viewForward;
  glm::vec4 background;
};

// shaders/glasses_lens.vert's grid: 8 rings of 48 quads, two triangles each.
constexpr std::uint32_t kLensVertices = 8 * 48 * 6;

}  // namespace

GlassesPass::GlassesPass(const Device& device, const SurfaceScene& scene, const RenderTarget& target)
    : scene_(&scene), target_(&target) {
  behind_ = Image(device, {.extent = target.extent(),
                           .format = RenderTarget::kHdrFormat,
                           .usage = vk::ImageUsageFlagBits::eTransferDst | vk::ImageUsageFlagBits::eSampled});
  view_ = Buffer(device, sizeof(GlassesView), vk::BufferUsageFlagBits::eUniformBuffer,
                 vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
  const vk::ShaderStageFlags fragment = vk::ShaderStageFlagBits::eFragment;
  layout_ = makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, fragment},
                                   {vk::DescriptorType::eCombinedImageSampler, fragment},
                                   {vk::DescriptorType::eUniformBuffer, fragment}});
  pool_ = makeDescriptorPool(device, 1,
                             {{vk::DescriptorType::eCombinedImageSampler, 2}, {vk::DescriptorType::eUniformBuffer, 1}});
  set_ = allocateSet(device, pool_, layout_);
  writeSampledImage(device, set_, 0, behind_, sampler_);
  // Read by texel; a depth format need not support linear filtering.
  depthSampler_ = vk::raii::Sampler(
      device.device(), vk::SamplerCreateInfo{.magFilter = vk::Filter::eNearest, .minFilter = vk::Filter::eNearest});
  writeSampledImage(device, set_, 1, target.depth(), depthSampler_);
  writeUniformBuffer(device, set_, 2, view_);
  pipeline_ = makeGraphicsPipeline(
      device,
      GraphicsPipelineSettings{.vertexShader = "glasses_lens.vert",
                               .fragmentShader = target.multisampled() ? "glasses_lens_msaa.frag" : "glasses_lens.frag",
                               .colorFormats = {RenderTarget::kHdrFormat},
                               .setLayouts = {scene.frameLayout(), *layout_},
                               .pushConstants = {{vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment,
                                                  0, sizeof(LensConstants)}}});
}

void GlassesPass::prepare(const FrameInput& frame, float aspect) {
  const GlassesView view{.clipToWorld = glm::inverse(frame.camera.projection(aspect) * frame.camera.view()),
                         .viewForward = glm::vec4(glm::normalize(frame.camera.target - frame.camera.position), 0.0f),
                         .background = glm::vec4(frame.background, 1.0f)};
  std::memcpy(view_.mapped().data(), &view, sizeof(view));
}

void GlassesPass::declareCopy(FrameGraph::Builder& pass) const {
  pass.read(target_->hdr(), ResourceUse::transferSource());
  pass.write(behind_, ResourceUse::transferDestination(), Contents::kDiscard);
}

void GlassesPass::recordCopy(const vk::raii::CommandBuffer& commands) const {
  const vk::ImageSubresourceLayers colour{.aspectMask = vk::ImageAspectFlagBits::eColor, .layerCount = 1};
  const vk::Extent2D extent = target_->extent();
  commands.copyImage(
      *target_->hdr().image(), vk::ImageLayout::eTransferSrcOptimal, *behind_.image(),
      vk::ImageLayout::eTransferDstOptimal,
      {vk::ImageCopy{.srcSubresource = colour, .dstSubresource = colour, .extent = {extent.width, extent.height, 1}}});
}

void GlassesPass::declareDraw(FrameGraph::Builder& pass) const {
  const auto fragment = vk::PipelineStageFlagBits2::eFragmentShader;
  pass.read(behind_, ResourceUse::sampled(fragment));
  pass.read(target_->depth(), ResourceUse::sampled(fragment));
  pass.write(target_->hdr(), ResourceUse::colorAttachment());
}

void GlassesPass::recordDraw(const vk::raii::CommandBuffer& commands, std::span<const Lens> lenses) const {
  const vk::RenderingAttachmentInfo colour{.imageView = *target_->hdr().view(),
                                           .imageLayout = vk::ImageLayout::eColorAttachmentOptimal,
                                           .loadOp = vk::AttachmentLoadOp::eLoad,
                                           .storeOp = vk::AttachmentStoreOp::eStore};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = target_->extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &colour});
  setViewportAndScissor(commands, target_->extent());
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline_.layout, 0, {*scene_->frameSet(), *set_}, {});
  for (const Lens& lens : lenses) {
    const LensShape& shape = lens.shape;
    const LensConstants constants{
        .model = lens.model,
        .surfaces = {shape.frontCurvature, shape.backCurvature, shape.centreThickness, shape.ior},
        .outline = {shape.halfAperture, 0.0f, 0.0f},
        .transmittance = glm::vec4(shape.transmittance, 1.0f)};
    commands.pushConstants<LensConstants>(
        *pipeline_.layout, vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment, 0, constants);
    commands.draw(kLensVertices, 1, 0, 0);
  }
  commands.endRendering();
}

}  // namespace mane::render
