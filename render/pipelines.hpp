#pragma once
// Shader modules from the embedded SPIR-V and a builder for the graphics pipelines of the
// passes (dynamic rendering: no render pass or framebuffer objects).

#include <string>
#include <string_view>
#include <vector>

#include "render/device.hpp"

namespace mane::render {

/// A shader module for the embedded shader `name` ("lambert.frag"); throws when the build
/// has no such shader (a programming error, not bad input).
vk::raii::ShaderModule loadShader(const Device& device, std::string_view name);

enum class Blend { kNone, kAdditive, kPremultipliedAlpha };

/// Values of a shader's specialization constants: value i is constant_id i, a 32-bit int, uint
/// or bool. Branches on them are removed when the pipeline is compiled, which matters on lavapipe:
/// it runs both sides of a branch on a uniform it cannot see through.
using SpecializationConstants = std::vector<std::uint32_t>;

struct GraphicsPipelineSettings {
  std::string vertexShader;
  std::string fragmentShader;  ///< empty: no fragment stage (depth-only passes)
  std::vector<vk::VertexInputBindingDescription> vertexBindings;
  std::vector<vk::VertexInputAttributeDescription> vertexAttributes;
  vk::PrimitiveTopology topology = vk::PrimitiveTopology::eTriangleList;
  bool dynamicLineWidth = false;  ///< set the line width when recording (vkCmdSetLineWidth); else 1
  vk::CullModeFlags cullMode = vk::CullModeFlagBits::eNone;
  /// Set the cull mode and front face when recording (vkCmdSetCullMode, vkCmdSetFrontFace);
  /// else `cullMode` with counter-clockwise front faces.
  bool dynamicCulling = false;
  std::vector<vk::Format> colorFormats;
  Blend blend = Blend::kNone;
  vk::Format depthFormat = vk::Format::eUndefined;
  bool depthTest = false;
  bool depthWrite = false;
  vk::CompareOp depthCompare = vk::CompareOp::eLessOrEqual;  ///< passes when (fragment OP stored)
  vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  std::vector<vk::DescriptorSetLayout> setLayouts;
  std::vector<vk::PushConstantRange> pushConstants;
  SpecializationConstants constants;  ///< for both stages
};

struct Pipeline {
  vk::raii::PipelineLayout layout{nullptr};
  vk::raii::Pipeline pipeline{nullptr};
};

/// Viewport and scissor are dynamic state (and the line width where asked); set them when recording.
Pipeline makeGraphicsPipeline(const Device& device, const GraphicsPipelineSettings& settings);

/// A compute pipeline running the embedded shader `shader` with one descriptor set,
/// `pushConstantBytes` of push constants (0 for none) and specialization `constants`.
Pipeline makeComputePipeline(const Device& device, std::string_view shader,
                             const vk::raii::DescriptorSetLayout& setLayout, std::uint32_t pushConstantBytes = 0,
                             const SpecializationConstants& constants = {});

/// A viewport covering `extent` with depth 0..1, and the matching scissor, set on `commands`.
void setViewportAndScissor(const vk::raii::CommandBuffer& commands, vk::Extent2D extent);

}  // namespace mane::render
