#pragma once
// The pre-integrated skin table on the GPU: a compute shader (shaders/preintegrated_skin.comp)
// bakes the table that render/luts/preintegrated_skin.hpp defines — RGB the diffuse ring
// integral over (N·L, 1/r), A the encoded Beckmann term over (N·H, α) — for one
// PreintegratedSkinSettings. A skin pass samples it with the functions of
// shaders/preintegrated_skin.glsl: one texture serves diffuse and specular.
//
// Format: R16F, four layers of a 2D array, one per channel (R, G, B, A). A skin fragment reads
// each diffuse channel at an N·L of its own (blurred normals) and the Beckmann term at N·H, so
// every lookup uses one channel, and lavapipe filters one channel for less than four. Every
// Vulkan device filters R16F linearly; storing to it takes shaderStorageImageExtendedFormats,
// which lavapipe and desktop GPUs have (create() names the format where a device lacks it).
// The values stored lie in [0, 1] (the diffuse term, and 0.5·D^0.1 of the Beckmann term but for
// its peak at α < 0.018), where half floats step by ≤ 2^-11: storage errors ≤ 4.9e-4 even where
// a write rounds toward zero (Vulkan leaves the rounding to the device), about the 256-texel
// table's own bilinear error and inside the 1e-3 the tests ask; the decoded Beckmann term keeps
// ≤ 1 %. 32-bit texels would double the memory for precision the lookups cannot use. No mip
// maps: the table varies smoothly except along 1/r ≈ 0, where a minified lookup should not blur
// the terminator.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/frame.hpp"
#include "render/luts/preintegrated_skin.hpp"
#include "render/resources.hpp"

namespace mane::render {

class PreintegratedSkinLut {
public:
  static constexpr vk::Format kFormat = vk::Format::eR16Sfloat;
  static constexpr std::uint32_t kLayers = 4;  ///< R, G, B, A

  /// Bakes the table for `settings` and waits for the GPU. Errors: invalid settings (validate()),
  /// a device that cannot store to or linearly filter kFormat, or a Vulkan failure.
  static Result<PreintegratedSkinLut> create(const Device& device, const PreintegratedSkinSettings& settings = {});

  PreintegratedSkinLut(PreintegratedSkinLut&&) noexcept = default;
  PreintegratedSkinLut& operator=(PreintegratedSkinLut&&) noexcept = default;

  /// The table, SHADER_READ_ONLY layout: a sampler2DArray.
  const vk::raii::ImageView& view() const { return table_.view(); }
  /// Bilinear, clamped to the edges: what shaders/preintegrated_skin.glsl expects.
  const vk::raii::Sampler& sampler() const { return sampler_; }
  const PreintegratedSkinSettings& settings() const { return settings_; }
  vk::Extent2D extent() const { return table_.extent(); }
  /// GPU time of the bake ("preintegrated skin"); empty without timestamps.
  const std::vector<PassTiming>& bakeTimings() const { return timings_; }

  /// The texels read back to the host (for tests and tools): texel (i, j) at j·size + i, half
  /// floats widened.
  Result<std::vector<glm::vec4>> readTexels() const;

private:
  PreintegratedSkinLut() = default;
  void bake();

  const Device* device_ = nullptr;
  PreintegratedSkinSettings settings_;
  Image table_;
  vk::raii::Sampler sampler_{nullptr};
  std::vector<PassTiming> timings_;
};

}  // namespace mane::render
