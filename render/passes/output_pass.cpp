#include "render/passes/output_pass.hpp"

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

// Push constants of shaders/output.frag.
struct OutputConstants {
  glm::vec2 overlayUvScale;
  float exposure;
};

}  // namespace

OutputPass::OutputPass(const Device& device, const RenderTarget& target, const PostPass& post)
    : device_(&device), post_(&post) {
  const vk::ShaderStageFlags fragment = vk::ShaderStageFlagBits::eFragment;
  layout_ = makeSetLayout(device, {{vk::DescriptorType::eCombinedImageSampler, fragment},
                                   {vk::DescriptorType::eCombinedImageSampler, fragment}});
  sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
  pool_ = makeDescriptorPool(device, 1, {{vk::DescriptorType::eCombinedImageSampler, 2}});
  set_ = allocateSet(device, pool_, layout_);
  writeSampledImage(device, set_, 0, target.hdr(), sampler_);
  // The overlay stays in GENERAL layout (the post chain writes it as a storage image).
  writeSampledImage(device, set_, 1, post.overlay().view(), post.sampler(), vk::ImageLayout::eGeneral);
  pipelineFor(ToneMapping::kLinear, PostPass::OverlayUse::kNone);
}

const Pipeline& OutputPass::pipelineFor(ToneMapping toneMapping, PostPass::OverlayUse overlay) {
  Pipeline& pipeline = pipelines_[3 * std::size_t(toneMapping == ToneMapping::kReinhard) + std::size_t(overlay)];
  if (*pipeline.pipeline) return pipeline;
  pipeline = makeGraphicsPipeline(
      *device_,
      GraphicsPipelineSettings{.vertexShader = "fullscreen.vert",
                               .fragmentShader = "output.frag",
                               .colorFormats = {RenderTarget::kOutputFormat},
                               .setLayouts = {*layout_},
                               .pushConstants = {{vk::ShaderStageFlagBits::eFragment, 0, sizeof(OutputConstants)}},
                               .constants = {std::uint32_t(toneMapping), std::uint32_t(overlay)}});
  return pipeline;
}

void OutputPass::declare(FrameGraph::Builder& pass, const RenderTarget& target, const PostSettings& post) const {
  const auto fragment = vk::PipelineStageFlagBits2::eFragmentShader;
  pass.read(target.hdr(), ResourceUse::sampled(fragment));
  if (PostPass::runs(post))
    pass.read(post_->overlay(), {fragment, vk::AccessFlagBits2::eShaderSampledRead, vk::ImageLayout::eGeneral});
  pass.write(target.output(), ResourceUse::colorAttachment(), Contents::kDiscard);
}

void OutputPass::record(const vk::raii::CommandBuffer& commands, const RenderTarget& target, float exposure,
                        const PostSettings& post) {
  // The chain's overlay only where it ran this frame (the renderer records it as `post` asks).
  const PostPass::OverlayUse overlay = PostPass::runs(post) ? post_->overlayUse() : PostPass::OverlayUse::kNone;
  const Pipeline& pipeline = pipelineFor(post.toneMapping, overlay);
  const vk::RenderingAttachmentInfo color{.imageView = *target.output().view(),
                                          .imageLayout = vk::ImageLayout::eColorAttachmentOptimal,
                                          .loadOp = vk::AttachmentLoadOp::eDontCare,
                                          .storeOp = vk::AttachmentStoreOp::eStore};
  commands.beginRendering(vk::RenderingInfo{.renderArea = {.extent = target.extent()},
                                            .layerCount = 1,
                                            .colorAttachmentCount = 1,
                                            .pColorAttachments = &color});
  setViewportAndScissor(commands, target.extent());
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline.layout, 0, {*set_}, {});
  const OutputConstants constants{.overlayUvScale = post_->overlayUvScale(), .exposure = exposure};
  commands.pushConstants<OutputConstants>(*pipeline.layout, vk::ShaderStageFlagBits::eFragment, 0, constants);
  commands.draw(3, 1, 0, 0);
  commands.endRendering();
}

}  // namespace mane::render
