#include "render/descriptors.hpp"

#include <vector>

namespace mane::render {

vk::raii::DescriptorSetLayout makeSetLayout(
    const Device& device, std::initializer_list<std::pair<vk::DescriptorType, vk::ShaderStageFlags>> bindings) {
  std::vector<vk::DescriptorSetLayoutBinding> entries;
  for (const auto& [type, stages] : bindings)
    entries.push_back({.binding = static_cast<std::uint32_t>(entries.size()),
                       .descriptorType = type,
                       .descriptorCount = 1,
                       .stageFlags = stages});
  return vk::raii::DescriptorSetLayout(
      device.device(), vk::DescriptorSetLayoutCreateInfo{.bindingCount = static_cast<std::uint32_t>(entries.size()),
                                                         .pBindings = entries.data()});
}

vk::raii::DescriptorPool makeDescriptorPool(const Device& device, std::uint32_t maxSets,
                                            std::initializer_list<vk::DescriptorPoolSize> sizes) {
  return vk::raii::DescriptorPool(
      device.device(), vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                                                    .maxSets = maxSets,
                                                    .poolSizeCount = static_cast<std::uint32_t>(sizes.size()),
                                                    .pPoolSizes = std::data(sizes)});
}

vk::raii::DescriptorSet allocateSet(const Device& device, const vk::raii::DescriptorPool& pool,
                                    const vk::raii::DescriptorSetLayout& layout) {
  vk::raii::DescriptorSets sets(
      device.device(),
      vk::DescriptorSetAllocateInfo{.descriptorPool = *pool, .descriptorSetCount = 1, .pSetLayouts = &*layout});
  return std::move(sets.front());
}

void writeUniformBuffer(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                        const Buffer& buffer) {
  const vk::DescriptorBufferInfo info{.buffer = *buffer.buffer(), .offset = 0, .range = buffer.size()};
  device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set,
                                                              .dstBinding = binding,
                                                              .descriptorCount = 1,
                                                              .descriptorType = vk::DescriptorType::eUniformBuffer,
                                                              .pBufferInfo = &info},
                                       {});
}

void writeStorageBuffer(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                        const Buffer& buffer) {
  const vk::DescriptorBufferInfo info{.buffer = *buffer.buffer(), .offset = 0, .range = buffer.size()};
  device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set,
                                                              .dstBinding = binding,
                                                              .descriptorCount = 1,
                                                              .descriptorType = vk::DescriptorType::eStorageBuffer,
                                                              .pBufferInfo = &info},
                                       {});
}

vk::raii::BufferView makeTexelView(const Device& device, vk::Buffer buffer, vk::Format format) {
  return vk::raii::BufferView(device.device(),
                              vk::BufferViewCreateInfo{.buffer = buffer, .format = format, .range = VK_WHOLE_SIZE});
}

void writeUniformTexelBuffer(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                             const vk::raii::BufferView& view) {
  const vk::BufferView handle = *view;
  device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set,
                                                              .dstBinding = binding,
                                                              .descriptorCount = 1,
                                                              .descriptorType = vk::DescriptorType::eUniformTexelBuffer,
                                                              .pTexelBufferView = &handle},
                                       {});
}

void writeSampledImage(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                       const Image& image, const vk::raii::Sampler& sampler) {
  writeSampledImage(device, set, binding, image.view(), sampler);
}

void writeSampledImage(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                       const vk::raii::ImageView& view, const vk::raii::Sampler& sampler, vk::ImageLayout layout) {
  const vk::DescriptorImageInfo info{.sampler = *sampler, .imageView = *view, .imageLayout = layout};
  device.device().updateDescriptorSets(
      vk::WriteDescriptorSet{.dstSet = *set,
                             .dstBinding = binding,
                             .descriptorCount = 1,
                             .descriptorType = vk::DescriptorType::eCombinedImageSampler,
                             .pImageInfo = &info},
      {});
}

void writeStorageImage(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                       const vk::raii::ImageView& view) {
  const vk::DescriptorImageInfo info{.imageView = *view, .imageLayout = vk::ImageLayout::eGeneral};
  device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set,
                                                              .dstBinding = binding,
                                                              .descriptorCount = 1,
                                                              .descriptorType = vk::DescriptorType::eStorageImage,
                                                              .pImageInfo = &info},
                                       {});
}

}  // namespace mane::render
