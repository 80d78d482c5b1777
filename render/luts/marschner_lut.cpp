#include "render/luts/marschner_lut.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

#include <glm/gtc/packing.hpp>

#include "render/descriptors.hpp"
#include "render/gpu_timer.hpp"
#include "render/pipelines.hpp"

namespace mane::render {

namespace {

// Mirrors the push constants of shaders/marschner_lut.comp.
struct BakeConstants {
  glm::vec4 absorption;  // xyz σa, w η
  glm::vec4 shifts;      // xyz α_p, w β_N
  glm::vec4 widths;      // xyz β_p
  glm::uvec4 sizes;      // x M size, y N width, z N height, w h nodes
  glm::uvec4 table;      // x 0 = M, 1 = N
};
static_assert(sizeof(BakeConstants) == 80);

constexpr std::uint32_t kWorkgroupSize = 8;  // local_size_x/y of the shader

using Stage = vk::PipelineStageFlagBits2;
using Access = vk::AccessFlagBits2;
using Layout = vk::ImageLayout;

Result<void> checkFormat(const Device& device, vk::Format format) {
  const vk::FormatFeatureFlags needed =
      vk::FormatFeatureFlagBits::eStorageImage | vk::FormatFeatureFlagBits::eSampledImage |
      vk::FormatFeatureFlagBits::eSampledImageFilterLinear | vk::FormatFeatureFlagBits::eBlitSrc |
      vk::FormatFeatureFlagBits::eBlitDst | vk::FormatFeatureFlagBits::eTransferSrc;
  const vk::FormatFeatureFlags present = device.physicalDevice().getFormatProperties(format).optimalTilingFeatures;
  if ((present & needed) != needed)
    return fail("Marschner lookup tables: " + device.info().name + " cannot store, blit and linearly filter " +
                vk::to_string(format) + " images (has " + vk::to_string(present) + ")");
  return {};
}

// Blits each level of `image` from the one above it (a 2×2 box filter when sizes halve), the
// Image::texture scheme with layers. Expects level 0 in GENERAL after compute writes; leaves all
// levels SHADER_READ_ONLY for fragment and compute shaders.
void buildMips(const vk::raii::CommandBuffer& commands, vk::Image image, vk::Extent2D extent, std::uint32_t layers,
               std::uint32_t levels) {
  const auto range = [&](std::uint32_t level, std::uint32_t count) {
    return vk::ImageSubresourceRange{vk::ImageAspectFlagBits::eColor, level, count, 0, layers};
  };
  imageBarrier(commands, image, range(0, 1), Layout::eGeneral, Layout::eTransferSrcOptimal, Stage::eComputeShader,
               Access::eShaderStorageWrite, Stage::eBlit, Access::eTransferRead);
  if (levels > 1)
    imageBarrier(commands, image, range(1, levels - 1), Layout::eUndefined, Layout::eTransferDstOptimal, Stage::eNone,
                 Access::eNone, Stage::eBlit, Access::eTransferWrite);
  auto w = static_cast<std::int32_t>(extent.width), h = static_cast<std::int32_t>(extent.height);
  for (std::uint32_t level = 1; level < levels; ++level) {
    const std::int32_t nw = std::max(w / 2, 1), nh = std::max(h / 2, 1);
    const vk::ImageBlit blit{.srcSubresource = {vk::ImageAspectFlagBits::eColor, level - 1, 0, layers},
                             .srcOffsets = std::array{vk::Offset3D{0, 0, 0}, vk::Offset3D{w, h, 1}},
                             .dstSubresource = {vk::ImageAspectFlagBits::eColor, level, 0, layers},
                             .dstOffsets = std::array{vk::Offset3D{0, 0, 0}, vk::Offset3D{nw, nh, 1}}};
    commands.blitImage(image, Layout::eTransferSrcOptimal, image, Layout::eTransferDstOptimal, blit,
                       vk::Filter::eLinear);
    imageBarrier(commands, image, range(level, 1), Layout::eTransferDstOptimal, Layout::eTransferSrcOptimal,
                 Stage::eBlit, Access::eTransferWrite, Stage::eBlit, Access::eTransferRead);
    w = nw;
    h = nh;
  }
  imageBarrier(commands, image, range(0, levels), Layout::eTransferSrcOptimal, Layout::eShaderReadOnlyOptimal,
               Stage::eBlit, Access::eTransferRead, Stage::eFragmentShader | Stage::eComputeShader,
               Access::eShaderSampledRead);
}

}  // namespace

MarschnerLut::Table MarschnerLut::makeTable(const Device& device, vk::Extent2D extent, std::uint32_t layers,
                                            vk::Format format) {
  Table table;
  table.extent = extent;
  table.layers = layers;
  table.levels = static_cast<std::uint32_t>(std::bit_width(std::max(extent.width, extent.height)));
  table.format = format;
  table.image = vk::raii::Image(
      device.device(),
      vk::ImageCreateInfo{.imageType = vk::ImageType::e2D,
                          .format = format,
                          .extent = {extent.width, extent.height, 1},
                          .mipLevels = table.levels,
                          .arrayLayers = layers,
                          .samples = vk::SampleCountFlagBits::e1,
                          .tiling = vk::ImageTiling::eOptimal,
                          .usage = vk::ImageUsageFlagBits::eStorage | vk::ImageUsageFlagBits::eSampled |
                                   vk::ImageUsageFlagBits::eTransferSrc | vk::ImageUsageFlagBits::eTransferDst,
                          .initialLayout = vk::ImageLayout::eUndefined});
  table.allocation = Allocation(device, table.image.getMemoryRequirements(), vk::MemoryPropertyFlagBits::eDeviceLocal);
  table.image.bindMemory(*table.allocation.memory(), 0);
  table.view = vk::raii::ImageView(
      device.device(),
      vk::ImageViewCreateInfo{.image = *table.image,
                              .viewType = layers > 1 ? vk::ImageViewType::e2DArray : vk::ImageViewType::e2D,
                              .format = format,
                              .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, table.levels, 0, layers}});
  return table;
}

Result<MarschnerLut> MarschnerLut::create(const Device& device, const HairShadingParams& params) {
  if (auto valid = validate(params); !valid) return std::unexpected(valid.error());
  // M peaks near κ = 1/β² at the poles: half floats end at 65504, i.e. β ≥ 0.0039 rad.
  for (const HairLobe p : {HairLobe::kR, HairLobe::kTT, HairLobe::kTRT})
    if (params.lobe(p).width < kMinimumLobeWidth)
      return fail("Marschner lookup tables: lobe width " + std::to_string(params.lobe(p).width) +
                  " rad is below the tables' minimum of " + std::to_string(kMinimumLobeWidth) + " rad (0.5°)");
  if (auto ok = checkFormat(device, kLongitudinalFormat); !ok) return std::unexpected(ok.error());
  if (auto ok = checkFormat(device, kAzimuthalFormat); !ok) return std::unexpected(ok.error());
  MarschnerLut lut;
  lut.device_ = &device;
  lut.params_ = params;
  try {
    lut.longitudinal_ = makeTable(device, {kLongitudinalSize, kLongitudinalSize}, 1, kLongitudinalFormat);
    lut.azimuthal_ = makeTable(device, {kAzimuthalWidth, kAzimuthalHeight}, kAzimuthalLayers, kAzimuthalFormat);
    lut.sampler_ = makeLinearSampler(device, vk::SamplerAddressMode::eClampToEdge, 1.0f);
    lut.bake();
  } catch (const std::exception& error) {
    return fail(std::string("Marschner lookup tables: baking failed: ") + error.what());
  }
  return lut;
}

void MarschnerLut::bake() {
  const Device& device = *device_;
  // The compute pipeline and the level-0 storage views live only for the bake.
  const vk::raii::DescriptorSetLayout setLayout =
      makeSetLayout(device, {{vk::DescriptorType::eStorageImage, vk::ShaderStageFlagBits::eCompute},
                             {vk::DescriptorType::eStorageImage, vk::ShaderStageFlagBits::eCompute}});
  const Pipeline pipeline = makeComputePipeline(device, "marschner_lut.comp", setLayout, sizeof(BakeConstants));

  const auto levelZeroView = [&](const Table& table) {
    return vk::raii::ImageView(
        device.device(),
        vk::ImageViewCreateInfo{.image = *table.image,
                                .viewType = table.layers > 1 ? vk::ImageViewType::e2DArray : vk::ImageViewType::e2D,
                                .format = table.format,
                                .subresourceRange = {vk::ImageAspectFlagBits::eColor, 0, 1, 0, table.layers}});
  };
  const vk::raii::ImageView longitudinalStorage = levelZeroView(longitudinal_);
  const vk::raii::ImageView azimuthalStorage = levelZeroView(azimuthal_);
  const vk::raii::DescriptorPool pool = makeDescriptorPool(device, 1, {{vk::DescriptorType::eStorageImage, 2}});
  const vk::raii::DescriptorSet set = allocateSet(device, pool, setLayout);
  const std::array images{
      vk::DescriptorImageInfo{.imageView = *longitudinalStorage, .imageLayout = vk::ImageLayout::eGeneral},
      vk::DescriptorImageInfo{.imageView = *azimuthalStorage, .imageLayout = vk::ImageLayout::eGeneral}};
  device.device().updateDescriptorSets(vk::WriteDescriptorSet{.dstSet = *set,
                                                              .dstBinding = 0,
                                                              .descriptorCount = 2,
                                                              .descriptorType = vk::DescriptorType::eStorageImage,
                                                              .pImageInfo = images.data()},
                                       {});

  BakeConstants constants{
      .absorption = glm::vec4(params_.absorption, params_.refractiveIndex),
      .shifts = glm::vec4(params_.r.shift, params_.tt.shift, params_.trt.shift, params_.azimuthalWidth),
      .widths = glm::vec4(params_.r.width, params_.tt.width, params_.trt.width, 0.0f),
      .sizes = glm::uvec4(kLongitudinalSize, kAzimuthalWidth, kAzimuthalHeight, kAzimuthalNodes),
      .table = glm::uvec4(0u)};

  GpuTimer timer(device, 3);
  device.submitAndWait([&](const vk::raii::CommandBuffer& commands) {
    timer.reset(commands);
    for (const Table* table : {&longitudinal_, &azimuthal_})
      imageBarrier(commands, *table->image, {vk::ImageAspectFlagBits::eColor, 0, table->levels, 0, table->layers},
                   Layout::eUndefined, Layout::eGeneral, Stage::eNone, Access::eNone, Stage::eComputeShader,
                   Access::eShaderStorageWrite);
    commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline.pipeline);
    commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline.layout, 0, *set, {});
    for (std::uint32_t which = 0; which < 2; ++which) {
      const Table& table = which == 0 ? longitudinal_ : azimuthal_;
      constants.table.x = which;
      const auto groups = [](std::uint32_t texels) { return (texels + kWorkgroupSize - 1) / kWorkgroupSize; };
      timer.begin(commands, which == 0 ? PassName("longitudinal") : PassName("azimuthal"));
      commands.pushConstants<BakeConstants>(*pipeline.layout, vk::ShaderStageFlagBits::eCompute, 0, constants);
      commands.dispatch(groups(table.extent.width), groups(table.extent.height), 1);
      timer.end(commands);
    }
    timer.begin(commands, PassName("mips"));
    buildMips(commands, *longitudinal_.image, longitudinal_.extent, longitudinal_.layers, longitudinal_.levels);
    buildMips(commands, *azimuthal_.image, azimuthal_.extent, azimuthal_.layers, azimuthal_.levels);
    timer.end(commands);
  });
  timings_ = timer.results();
}

std::uint32_t MarschnerLut::mipLevels(MarschnerTable table) const {
  return table == MarschnerTable::kLongitudinal ? longitudinal_.levels : azimuthal_.levels;
}

vk::Extent2D MarschnerLut::extent(MarschnerTable table) const {
  return table == MarschnerTable::kLongitudinal ? longitudinal_.extent : azimuthal_.extent;
}

Result<std::vector<glm::vec4>> MarschnerLut::readTexels(MarschnerTable which, std::uint32_t level) const {
  const Table& table = which == MarschnerTable::kLongitudinal ? longitudinal_ : azimuthal_;
  if (level >= table.levels)
    return fail("Marschner lookup tables: mip level " + std::to_string(level) + " of a table with " +
                std::to_string(table.levels) + " levels");
  const std::uint32_t width = std::max(table.extent.width >> level, 1u);
  const std::uint32_t height = std::max(table.extent.height >> level, 1u);
  const bool half = table.format == vk::Format::eR16G16B16A16Sfloat;
  const std::size_t texels = std::size_t(width) * height * table.layers;
  const vk::DeviceSize bytes = texels * (half ? 8 : 16);
  try {
    const Buffer host(*device_, bytes, vk::BufferUsageFlagBits::eTransferDst,
                      vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    device_->submitAndWait([&](const vk::raii::CommandBuffer& commands) {
      const vk::ImageSubresourceRange range{vk::ImageAspectFlagBits::eColor, level, 1, 0, table.layers};
      imageBarrier(commands, *table.image, range, Layout::eShaderReadOnlyOptimal, Layout::eTransferSrcOptimal,
                   Stage::eFragmentShader | Stage::eComputeShader, Access::eShaderSampledRead, Stage::eCopy,
                   Access::eTransferRead);
      commands.copyImageToBuffer(
          *table.image, Layout::eTransferSrcOptimal, *host.buffer(),
          vk::BufferImageCopy{.imageSubresource = {vk::ImageAspectFlagBits::eColor, level, 0, table.layers},
                              .imageExtent = {width, height, 1}});
      imageBarrier(commands, *table.image, range, Layout::eTransferSrcOptimal, Layout::eShaderReadOnlyOptimal,
                   Stage::eCopy, Access::eTransferRead, Stage::eFragmentShader | Stage::eComputeShader,
                   Access::eShaderSampledRead);
      const vk::MemoryBarrier2 toHost{.srcStageMask = Stage::eCopy,
                                      .srcAccessMask = Access::eTransferWrite,
                                      .dstStageMask = Stage::eHost,
                                      .dstAccessMask = Access::eHostRead};
      commands.pipelineBarrier2(vk::DependencyInfo{.memoryBarrierCount = 1, .pMemoryBarriers = &toHost});
    });
    std::vector<glm::vec4> result(texels);
    const std::byte* data = host.mapped().data();
    if (!half) {
      std::memcpy(result.data(), data, bytes);
      return result;
    }
    for (std::size_t i = 0; i < texels; ++i) {
      std::uint16_t h[4];
      std::memcpy(h, data + 8 * i, sizeof(h));
      result[i] = glm::vec4(glm::unpackHalf1x16(h[0]), glm::unpackHalf1x16(h[1]), glm::unpackHalf1x16(h[2]),
                            glm::unpackHalf1x16(h[3]));
    }
    return result;
  } catch (const std::exception& error) {
    return fail(std::string("Marschner lookup tables: read-back failed: ") + error.what());
  }
}

}  // namespace mane::render
