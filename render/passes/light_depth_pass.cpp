#include "render/passes/light_depth_pass.hpp"

#include <algorithm>

namespace mane::render {

void DrawnBounds::add(const BoundingSphere& local, const glm::mat4& model, float margin) {
  const glm::vec3 centre = glm::vec3(model * glm::vec4(local.centre, 1.0f));
  const float scale =
      std::max({glm::length(glm::vec3(model[0])), glm::length(glm::vec3(model[1])), glm::length(glm::vec3(model[2]))});
  lo_ = glm::min(lo_, centre - local.radius * scale * margin);
  hi_ = glm::max(hi_, centre + local.radius * scale * margin);
  empty_ = false;
}

BoundingSphere DrawnBounds::sphere() const {
  if (empty_) return {.centre = glm::vec3(0.0f), .radius = 1.0f};
  return {.centre = 0.5f * (lo_ + hi_), .radius = 0.5f * glm::length(hi_ - lo_) * 1.001f};
}

LightDepthPass::LightDepthPass(const Device& device, std::uint32_t vertexStride)
    : depth_(device, {.extent = {kResolution, kResolution},
                      .format = kFormat,
                      .usage = vk::ImageUsageFlagBits::eDepthStencilAttachment | vk::ImageUsageFlagBits::eSampled,
                      .aspect = vk::ImageAspectFlagBits::eDepth}),
      sampler_(device.device(), vk::SamplerCreateInfo{.magFilter = vk::Filter::eNearest,
                                                      .minFilter = vk::Filter::eNearest,
                                                      .addressModeU = vk::SamplerAddressMode::eClampToEdge,
                                                      .addressModeV = vk::SamplerAddressMode::eClampToEdge,
                                                      .addressModeW = vk::SamplerAddressMode::eClampToEdge,
                                                      .maxLod = 0.0f}) {
  pipeline_ = makeGraphicsPipeline(
      device, GraphicsPipelineSettings{
                  .vertexShader = "light_depth.vert",
                  .vertexBindings = {{.binding = 0, .stride = vertexStride, .inputRate = vk::VertexInputRate::eVertex}},
                  .vertexAttributes = {{0, 0, vk::Format::eR32G32B32Sfloat, 0}},
                  // Both faces: the first surface the light meets, whichever way it is wound.
                  .cullMode = vk::CullModeFlagBits::eNone,
                  .depthFormat = kFormat,
                  .depthTest = true,
                  .depthWrite = true,
                  .pushConstants = {{vk::ShaderStageFlagBits::eVertex, 0, sizeof(glm::mat4)}}});
  // Readable from the start: pipelines that compile the lookup out still bind it.
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    imageBarrier(commands, *depth_.image(), {vk::ImageAspectFlagBits::eDepth, 0, 1, 0, 1}, vk::ImageLayout::eUndefined,
                 vk::ImageLayout::eShaderReadOnlyOptimal, vk::PipelineStageFlagBits2::eNone, vk::AccessFlagBits2::eNone,
                 vk::PipelineStageFlagBits2::eFragmentShader, vk::AccessFlagBits2::eShaderSampledRead);
  });
}

void LightDepthPass::prepare(glm::vec3 towardLight, const BoundingSphere& bounds, bool drawsAnything) {
  const float diameter = 2.0f * bounds.radius;
  uniforms_ = {.lightFromWorld = orthographicLightFrame(towardLight, bounds),
               .scale = {diameter, 1.0f / kResolution, diameter / kResolution, drawsAnything ? 1.0f : 0.0f}};
}

void LightDepthPass::declare(FrameGraph::Builder& pass) const {
  pass.write(depth_, ResourceUse::depthAttachment(), Contents::kDiscard);
}

void LightDepthPass::execute(const vk::raii::CommandBuffer& commands, std::span<const LightDepthDraw> draws) const {
  using Layout = vk::ImageLayout;
  const vk::RenderingAttachmentInfo attachment{.imageView = *depth_.view(),
                                               .imageLayout = Layout::eDepthAttachmentOptimal,
                                               .loadOp = vk::AttachmentLoadOp::eClear,
                                               .storeOp = vk::AttachmentStoreOp::eStore,
                                               .clearValue = {.depthStencil = {.depth = 1.0f, .stencil = 0}}};
  commands.beginRendering(
      vk::RenderingInfo{.renderArea = {.extent = depth_.extent()}, .layerCount = 1, .pDepthAttachment = &attachment});
  setViewportAndScissor(commands, depth_.extent());
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_.pipeline);
  for (const LightDepthDraw& draw : draws) {
    commands.pushConstants<glm::mat4>(*pipeline_.layout, vk::ShaderStageFlagBits::eVertex, 0,
                                      uniforms_.lightFromWorld * draw.model);
    commands.bindVertexBuffers(0, {draw.vertices}, {vk::DeviceSize{0}});
    commands.bindIndexBuffer(draw.indices, 0, vk::IndexType::eUint32);
    commands.drawIndexed(draw.indexCount, 1, 0, 0, 0);
  }
  commands.endRendering();
}

}  // namespace mane::render
