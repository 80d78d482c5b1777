#include "render/pipelines.hpp"

#include <stdexcept>

#include "shaders/embedded.hpp"

namespace mane::render {

vk::raii::ShaderModule loadShader(const Device& device, std::string_view name) {
  const auto words = shaders::findSpirv(name);
  if (!words) throw std::logic_error("no embedded shader named " + std::string(name));
  return vk::raii::ShaderModule(device.device(),
                                vk::ShaderModuleCreateInfo{.codeSize = words->size_bytes(), .pCode = words->data()});
}

namespace {

// Constant i at byte 4i of the values.
struct Specialization {
  std::vector<vk::SpecializationMapEntry> entries;
  vk::SpecializationInfo info;

  explicit Specialization(const SpecializationConstants& values) {
    for (std::uint32_t i = 0; i < values.size(); ++i) entries.push_back({.constantID = i, .offset = 4 * i, .size = 4});
    info = vk::SpecializationInfo{.mapEntryCount = static_cast<std::uint32_t>(entries.size()),
                                  .pMapEntries = entries.data(),
                                  .dataSize = 4 * values.size(),
                                  .pData = values.data()};
  }
  const vk::SpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

}  // namespace

Pipeline makeGraphicsPipeline(const Device& device, const GraphicsPipelineSettings& settings) {
  Pipeline result;
  result.layout = vk::raii::PipelineLayout(
      device.device(),
      vk::PipelineLayoutCreateInfo{.setLayoutCount = static_cast<std::uint32_t>(settings.setLayouts.size()),
                                   .pSetLayouts = settings.setLayouts.data(),
                                   .pushConstantRangeCount = static_cast<std::uint32_t>(settings.pushConstants.size()),
                                   .pPushConstantRanges = settings.pushConstants.data()});

  const vk::raii::ShaderModule vertex = loadShader(device, settings.vertexShader);
  const bool hasFragment = !settings.fragmentShader.empty();
  const vk::raii::ShaderModule fragment =
      hasFragment ? loadShader(device, settings.fragmentShader) : vk::raii::ShaderModule(nullptr);
  const Specialization specialization(settings.constants);
  std::vector<vk::PipelineShaderStageCreateInfo> stages{{.stage = vk::ShaderStageFlagBits::eVertex,
                                                         .module = *vertex,
                                                         .pName = "main",
                                                         .pSpecializationInfo = specialization.get()}};
  if (hasFragment)
    stages.push_back({.stage = vk::ShaderStageFlagBits::eFragment,
                      .module = *fragment,
                      .pName = "main",
                      .pSpecializationInfo = specialization.get()});
  const vk::PipelineVertexInputStateCreateInfo vertexInput{
      .vertexBindingDescriptionCount = static_cast<std::uint32_t>(settings.vertexBindings.size()),
      .pVertexBindingDescriptions = settings.vertexBindings.data(),
      .vertexAttributeDescriptionCount = static_cast<std::uint32_t>(settings.vertexAttributes.size()),
      .pVertexAttributeDescriptions = settings.vertexAttributes.data()};
  const vk::PipelineInputAssemblyStateCreateInfo inputAssembly{.topology = settings.topology};
  const vk::PipelineViewportStateCreateInfo viewport{.viewportCount = 1, .scissorCount = 1};
  const vk::PipelineRasterizationStateCreateInfo rasterization{.polygonMode = vk::PolygonMode::eFill,
                                                               .cullMode = settings.cullMode,
                                                               .frontFace = vk::FrontFace::eCounterClockwise,
                                                               .lineWidth = 1.0f};
  const vk::PipelineMultisampleStateCreateInfo multisample{.rasterizationSamples = settings.samples};
  const vk::PipelineDepthStencilStateCreateInfo depthStencil{.depthTestEnable = settings.depthTest,
                                                             .depthWriteEnable = settings.depthWrite,
                                                             .depthCompareOp = settings.depthCompare};

  vk::PipelineColorBlendAttachmentState blend{.colorWriteMask =
                                                  vk::ColorComponentFlagBits::eR | vk::ColorComponentFlagBits::eG |
                                                  vk::ColorComponentFlagBits::eB | vk::ColorComponentFlagBits::eA};
  if (settings.blend != Blend::kNone) {
    // Both modes take the source as is: additive sums (opacity maps), premultiplied alpha
    // composites over what is there.
    const vk::BlendFactor source = vk::BlendFactor::eOne;
    const vk::BlendFactor destination =
        settings.blend == Blend::kAdditive ? vk::BlendFactor::eOne : vk::BlendFactor::eOneMinusSrcAlpha;
    blend.blendEnable = VK_TRUE;
    blend.srcColorBlendFactor = source;
    blend.dstColorBlendFactor = destination;
    blend.colorBlendOp = vk::BlendOp::eAdd;
    blend.srcAlphaBlendFactor = source;
    blend.dstAlphaBlendFactor = destination;
    blend.alphaBlendOp = vk::BlendOp::eAdd;
  }
  const std::vector<vk::PipelineColorBlendAttachmentState> blends(settings.colorFormats.size(), blend);
  const vk::PipelineColorBlendStateCreateInfo colorBlend{.attachmentCount = static_cast<std::uint32_t>(blends.size()),
                                                         .pAttachments = blends.data()};
  std::vector dynamicStates{vk::DynamicState::eViewport, vk::DynamicState::eScissor};
  if (settings.dynamicLineWidth) dynamicStates.push_back(vk::DynamicState::eLineWidth);
  if (settings.dynamicCulling)
    dynamicStates.insert(dynamicStates.end(), {vk::DynamicState::eCullMode, vk::DynamicState::eFrontFace});
  const vk::PipelineDynamicStateCreateInfo dynamic{
      .dynamicStateCount = static_cast<std::uint32_t>(dynamicStates.size()), .pDynamicStates = dynamicStates.data()};
  const vk::PipelineRenderingCreateInfo rendering{
      .colorAttachmentCount = static_cast<std::uint32_t>(settings.colorFormats.size()),
      .pColorAttachmentFormats = settings.colorFormats.data(),
      .depthAttachmentFormat = settings.depthFormat};

  result.pipeline =
      vk::raii::Pipeline(device.device(), nullptr,
                         vk::GraphicsPipelineCreateInfo{.pNext = &rendering,
                                                        .stageCount = static_cast<std::uint32_t>(stages.size()),
                                                        .pStages = stages.data(),
                                                        .pVertexInputState = &vertexInput,
                                                        .pInputAssemblyState = &inputAssembly,
                                                        .pViewportState = &viewport,
                                                        .pRasterizationState = &rasterization,
                                                        .pMultisampleState = &multisample,
                                                        .pDepthStencilState = &depthStencil,
                                                        .pColorBlendState = &colorBlend,
                                                        .pDynamicState = &dynamic,
                                                        .layout = *result.layout});
  return result;
}

Pipeline makeComputePipeline(const Device& device, std::string_view shader,
                             const vk::raii::DescriptorSetLayout& setLayout, std::uint32_t pushConstantBytes,
                             const SpecializationConstants& constants) {
  Pipeline result;
  const vk::PushConstantRange push{
      .stageFlags = vk::ShaderStageFlagBits::eCompute, .offset = 0, .size = pushConstantBytes};
  result.layout = vk::raii::PipelineLayout(
      device.device(), vk::PipelineLayoutCreateInfo{.setLayoutCount = 1,
                                                    .pSetLayouts = &*setLayout,
                                                    .pushConstantRangeCount = pushConstantBytes > 0 ? 1u : 0u,
                                                    .pPushConstantRanges = &push});
  const vk::raii::ShaderModule module = loadShader(device, shader);
  const Specialization specialization(constants);
  result.pipeline =
      vk::raii::Pipeline(device.device(), nullptr,
                         vk::ComputePipelineCreateInfo{.stage = {.stage = vk::ShaderStageFlagBits::eCompute,
                                                                 .module = *module,
                                                                 .pName = "main",
                                                                 .pSpecializationInfo = specialization.get()},
                                                       .layout = *result.layout});
  return result;
}

void setViewportAndScissor(const vk::raii::CommandBuffer& commands, vk::Extent2D extent) {
  commands.setViewport(
      0, vk::Viewport{
             .width = static_cast<float>(extent.width), .height = static_cast<float>(extent.height), .maxDepth = 1.0f});
  commands.setScissor(0, vk::Rect2D{.extent = extent});
}

}  // namespace mane::render
