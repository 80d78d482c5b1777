#pragma once
// Small helpers for the descriptor sets of the passes: one binding per listed descriptor,
// numbered from 0.

#include <initializer_list>
#include <utility>

#include "render/resources.hpp"

namespace mane::render {

vk::raii::DescriptorSetLayout makeSetLayout(
    const Device& device, std::initializer_list<std::pair<vk::DescriptorType, vk::ShaderStageFlags>> bindings);

vk::raii::DescriptorPool makeDescriptorPool(const Device& device, std::uint32_t maxSets,
                                            std::initializer_list<vk::DescriptorPoolSize> sizes);

vk::raii::DescriptorSet allocateSet(const Device& device, const vk::raii::DescriptorPool& pool,
                                    const vk::raii::DescriptorSetLayout& layout);

void writeUniformBuffer(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                        const Buffer& buffer);

void writeStorageBuffer(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                        const Buffer& buffer);
void writeSampledImage(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                       const Image& image, const vk::raii::Sampler& sampler);
/// A view of the whole of `buffer` (which needs UNIFORM_TEXEL_BUFFER usage) as texels of `format`.
vk::raii::BufferView makeTexelView(const Device& device, vk::Buffer buffer, vk::Format format);
void writeUniformTexelBuffer(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                             const vk::raii::BufferView& view);
/// A storage image of `view` in GENERAL layout.
void writeStorageImage(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                       const vk::raii::ImageView& view);
/// A combined image sampler of `view` in `layout` (GENERAL for an image compute passes also
/// write as a storage image).
void writeSampledImage(const Device& device, const vk::raii::DescriptorSet& set, std::uint32_t binding,
                       const vk::raii::ImageView& view, const vk::raii::Sampler& sampler,
                       vk::ImageLayout layout = vk::ImageLayout::eShaderReadOnlyOptimal);

}  // namespace mane::render
