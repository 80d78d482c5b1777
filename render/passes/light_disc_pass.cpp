#include "render/passes/light_disc_pass.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace mane::render {
namespace {

// Push constants of shaders/light_disc.glsl.
struct LightDiscConstants {
  glm::mat4 ndcToDirection;
  glm::vec4 bounds;
  glm::vec4 towardLight;  // w: angular radius
  glm::vec4 radiance;
};

// The cone's rim is sampled at this many directions; their polygon, drawn around a circle
// 1/cos(π/n) wider, holds the disc's whole outline.
constexpr int kRimSamples = 32;

}  // namespace

std::optional<glm::vec4> discBounds(const glm::mat4& ndcFromDirection, glm::vec3 towardLight, float radius) {
  const glm::vec3 axis = glm::normalize(towardLight);
  // Any two unit vectors perpendicular to the axis and to each other.
  const glm::vec3 helper = std::abs(axis.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 a = glm::normalize(glm::cross(axis, helper));
  const glm::vec3 b = glm::cross(axis, a);
  // A little wider than the circumscribing polygon's circle: the edge's antialiasing reaches
  // half a pixel beyond the rim.
  const float rim = std::min(radius / std::cos(std::numbers::pi_v<float> / kRimSamples) * 1.02f + 1e-3f,
                             0.5f * std::numbers::pi_v<float>);
  glm::vec2 low(1e30f), high(-1e30f);
  int behind = 0;
  for (int k = 0; k < kRimSamples; ++k) {
    const float phi = 2.0f * std::numbers::pi_v<float> * float(k) / float(kRimSamples);
    const glm::vec3 direction =
        std::cos(rim) * axis + std::sin(rim) * (std::cos(phi) * a + std::sin(phi) * b);
    const glm::vec4 clip = ndcFromDirection * glm::vec4(direction, 0.0f);
    if (!(clip.w > 0.0f)) {
      ++behind;
      continue;
    }
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    low = glm::min(low, ndc);
    high = glm::max(high, ndc);
  }
  if (behind == kRimSamples) return std::nullopt;
  if (behind > 0) return glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f);
  low = glm::max(low, glm::vec2(-1.0f));
  high = glm::min(high, glm::vec2(1.0f));
  if (!(low.x < high.x && low.y < high.y)) return std::nullopt;
  return glm::vec4(low, high);
}

LightDiscPass::LightDiscPass(const Device& device, vk::Format colorFormat, vk::Format depthFormat,
                             vk::SampleCountFlagBits samples)
    : pipeline_(makeGraphicsPipeline(
          device, GraphicsPipelineSettings{
                      .vertexShader = "light_disc.vert",
                      .fragmentShader = "light_disc.frag",
                      .topology = vk::PrimitiveTopology::eTriangleStrip,
                      .colorFormats = {colorFormat},
                      .blend = Blend::kAdditive,
                      .depthFormat = depthFormat,
                      .depthTest = depthFormat != vk::Format::eUndefined,
                      .samples = samples,
                      .pushConstants = {{vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment, 0,
                                         sizeof(LightDiscConstants)}}})) {}

void LightDiscPass::draw(const vk::raii::CommandBuffer& commands, const Camera& camera,
                         std::span<const DirectionalLight> lights, vk::Extent2D extent) const {
  const float aspect = float(extent.width) / float(extent.height);
  // Directions only: the view without its translation.
  const glm::mat4 ndcFromDirection = camera.projection(aspect) * glm::mat4(glm::mat3(camera.view()));
  const glm::mat4 ndcToDirection = glm::inverse(ndcFromDirection);
  bool bound = false;
  for (const DirectionalLight& light : lights) {
    if (!(light.discRadius > 0.0f)) continue;
    const glm::vec3 towardLight = glm::normalize(light.direction);
    const std::optional<glm::vec4> bounds = discBounds(ndcFromDirection, towardLight, light.discRadius);
    if (!bounds) continue;
    if (!bound) {
      setViewportAndScissor(commands, extent);
      commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_.pipeline);
      bound = true;
    }
    const LightDiscConstants constants{
        .ndcToDirection = ndcToDirection,
        .bounds = *bounds,
        .towardLight = glm::vec4(towardLight, light.discRadius),
        .radiance = glm::vec4(light.color * light.discRadiance, 0.0f)};
    commands.pushConstants<LightDiscConstants>(*pipeline_.layout,
                                               vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment,
                                               0, constants);
    commands.draw(4, 1, 0, 0);
  }
}

}  // namespace mane::render
