#pragma once
// The sea: Gerstner waves on a projected grid, lit as deep water, with foam (NVIDIA's "Clear
// Sailing" demo, 2004).
//
// - "ocean" (compute, before the main pass): the projected grid (shaders/ocean_grid.comp),
//   OceanData::grid cells evenly spaced on the screen, each vertex moved to where its eye ray
//   meets the sea and displaced by the waves (shaders/ocean_waves.glsl, the GPU copy of
//   physics/ocean_waves.hpp's sum); only the rows over the sea (oceanGridRows) are computed and
//   drawn. Then the foam map, a square over the sea at rest, fades by 2^(−Δt/T½) and grows where
//   crests break (shaders/ocean_foam.comp).
// - In the main pass, after the surfaces and before the background: the grid's triangles
//   (shaders/ocean.vert), shaded by shaders/ocean.frag: the sky or environment and the first
//   light reflected by Fresnel, the light scattered up from below, foam, fog.
//
// The ocean's shaders bind the surfaces' frame set (SurfaceScene::frameLayout) as set 0 for the
// camera, the lights, the environment and the surfaces' shadow map, and their own as set 1.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "common/error.hpp"
#include "render/frame.hpp"
#include "render/frame_graph.hpp"
#include "render/pipelines.hpp"
#include "render/resources.hpp"

namespace mane::render {

/// The waves at one rest point, as the GPU evaluates them.
struct OceanProbeSample {
  glm::vec3 displacement{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  float jacobian = 1.0f;
};

/// The rows of the projected grid that a frame computes and draws: those over the sea.
struct GridRows {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

/// The projected grid's NDC extent: it overhangs the screen by a tenth on each side.
inline constexpr float kOceanGridOverhang = 1.1f;

/// The rows of a grid of `cells` over the overhanging screen whose eye rays meet the sea at rest
/// within `reach` of `eye`, and one more on each side (the others all end at the reach, so their
/// cells would collapse onto the horizon); every row with no sea in view or the eye not above it.
[[nodiscard]] GridRows oceanGridRows(const glm::mat4& clipToWorld, glm::vec3 eye, float reach, glm::uvec2 cells);

class OceanPass {
public:
  struct Formats {
    vk::Format color = vk::Format::eUndefined;
    vk::Format depth = vk::Format::eUndefined;
    vk::SampleCountFlagBits samples = vk::SampleCountFlagBits::e1;
  };

  /// Checks `ocean` (errors name the field and the wave) and creates the pass: its constants,
  /// the grid and the foam map. Drawing needs buildDrawPipeline() too.
  [[nodiscard]] static Result<std::unique_ptr<OceanPass>> create(const Device& device, const OceanData& ocean);
  /// The grid's pipeline, drawing into `formats` with the surfaces' frame set (of layout
  /// `frameLayout`) as set 0.
  [[nodiscard]] Result<void> buildDrawPipeline(const Formats& formats, vk::DescriptorSetLayout frameLayout);

  OceanPass(const OceanPass&) = delete;
  OceanPass& operator=(const OceanPass&) = delete;

  /// Writes this frame's constants: `frame.ocean`'s phases (one per wave; an error otherwise) and
  /// time step, and the camera for an image of `aspect`. Between frames.
  [[nodiscard]] Result<void> prepare(const FrameInput& frame, float aspect);

  /// The grid's vertices, then the foam map's fade and growth: one graph pass each.
  void declareGrid(FrameGraph::Builder& pass) const;
  void recordGrid(const vk::raii::CommandBuffer& commands) const;
  void declareFoam(FrameGraph::Builder& pass) const;
  void recordFoam(const vk::raii::CommandBuffer& commands) const;
  /// What the draw reads, for the main pass's declarations.
  void declareDrawReads(FrameGraph::Builder& pass) const;
  /// Records the grid inside the main pass, with the surfaces' frame set.
  void draw(const vk::raii::CommandBuffer& commands, const vk::raii::DescriptorSet& frameSet,
            vk::Extent2D extent) const;
  /// Where the foam map rests between frames, for the graph's last declaration.
  void leaveFoam(FrameGraph& graph) const;

  /// The waves at `rests` (x, z) with the phases of the last prepare(), evaluated on the GPU by
  /// the shaders' own sum, unfiltered; for tests. Waits for the device.
  [[nodiscard]] std::vector<OceanProbeSample> probe(std::span<const glm::vec2> rests) const;
  /// The foam map's texels, rows of increasing z, each of increasing x; for tests. Waits.
  [[nodiscard]] std::vector<float> readFoam() const;

private:
  OceanPass(const Device& device, const OceanData& ocean);

  const Device* device_;
  OceanData data_;
  Buffer uniforms_;  // OceanUniforms, host-visible
  Buffer indices_;   // the grid's triangles
  Buffer grid_;      // its vertices (shaders/ocean_grid.glsl)
  GridRows rows_{0, 0};  // this frame's, from prepare()
  Image foam_;  // R32F, GENERAL between frames
  vk::raii::Sampler foamSampler_{nullptr};
  vk::raii::DescriptorSetLayout drawLayout_{nullptr};
  vk::raii::DescriptorSetLayout foamLayout_{nullptr};
  vk::raii::DescriptorSetLayout gridLayout_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
  vk::raii::DescriptorSet drawSet_{nullptr};
  vk::raii::DescriptorSet foamSet_{nullptr};
  vk::raii::DescriptorSet gridSet_{nullptr};
  Pipeline drawPipeline_;
  Pipeline foamPipeline_;
  Pipeline gridPipeline_;
};

}  // namespace mane::render
