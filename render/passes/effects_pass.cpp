#include "render/passes/effects_pass.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "render/descriptors.hpp"

namespace mane::render {
namespace {

// Mirrors shaders/effects.vert's Record (std430).
struct Record {
  glm::vec4 a{0.0f};       // xyz: a sprite's centre, a line's start, a triangle's first corner; w: radius or half width
  glm::vec4 b{0.0f};       // xyz: a line's end, a triangle's second corner; w: the kind
  glm::vec4 c{0.0f};       // xyz: a triangle's third corner; w: a sprite's underside darkening
  glm::vec4 colour{0.0f};  // rgb albedo, a opacity
};
constexpr float kSprite = 0.0f;
constexpr float kLine = 1.0f;
constexpr float kTriangle = 2.0f;
constexpr std::uint32_t kVerticesPerRecord = 6;

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool albedo(const glm::vec3& v) {
  return finite(v) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f;
}
bool share(float v) {
  return v >= 0.0f && v <= 1.0f;
}

Result<void> validate(const EffectsFrame& effects) {
  const auto bad = [](const char* kind, std::size_t i, const char* field, const char* expected) {
    return fail(std::string("effects: ") + kind + " " + std::to_string(i) + "'s " + field + " must be " + expected +
                ".");
  };
  for (std::size_t i = 0; i < effects.sprites.size(); ++i) {
    const EffectSprite& s = effects.sprites[i];
    if (!finite(s.centre)) return bad("sprite", i, "centre", "finite");
    if (!(std::isfinite(s.radius) && s.radius > 0.0f)) return bad("sprite", i, "radius", "finite and > 0");
    if (!albedo(s.colour)) return bad("sprite", i, "colour", "finite and ≥ 0");
    if (!share(s.opacity)) return bad("sprite", i, "opacity", "in [0, 1]");
    if (!share(s.underside)) return bad("sprite", i, "underside", "in [0, 1]");
  }
  for (std::size_t i = 0; i < effects.lines.size(); ++i) {
    const EffectLine& l = effects.lines[i];
    if (!finite(l.from) || !finite(l.to)) return bad("line", i, "ends", "finite");
    if (!(std::isfinite(l.width) && l.width > 0.0f)) return bad("line", i, "width", "finite and > 0");
    if (!albedo(l.colour)) return bad("line", i, "colour", "finite and ≥ 0");
    if (!share(l.opacity)) return bad("line", i, "opacity", "in [0, 1]");
  }
  for (std::size_t i = 0; i < effects.triangles.size(); ++i) {
    const EffectTriangle& t = effects.triangles[i];
    if (!std::ranges::all_of(t.corners, finite)) return bad("triangle", i, "corners", "finite");
    if (!albedo(t.colour)) return bad("triangle", i, "colour", "finite and ≥ 0");
  }
  return {};
}

std::vector<Record> records(const EffectsFrame& effects) {
  std::vector<Record> result;
  result.reserve(effects.sprites.size() + effects.lines.size() + effects.triangles.size());
  for (const EffectSprite& s : effects.sprites)
    result.push_back({.a = glm::vec4(s.centre, s.radius),
                      .b = glm::vec4(s.centre, kSprite),
                      .c = glm::vec4(s.centre, s.underside),
                      .colour = glm::vec4(s.colour, s.opacity)});
  for (const EffectLine& l : effects.lines)
    result.push_back({.a = glm::vec4(l.from, 0.5f * l.width),
                      .b = glm::vec4(l.to, kLine),
                      .c = glm::vec4(0.5f * (l.from + l.to), 0.0f),
                      .colour = glm::vec4(l.colour, l.opacity)});
  for (const EffectTriangle& t : effects.triangles)
    result.push_back({.a = glm::vec4(t.corners[0], 0.0f),
                      .b = glm::vec4(t.corners[1], kTriangle),
                      .c = glm::vec4(t.corners[2], 0.0f),
                      .colour = glm::vec4(t.colour, 1.0f)});
  return result;
}

// Where a record is, for sorting: a sprite's centre, a line's middle, a triangle's centroid.
glm::vec3 middle(const Record& r) {
  if (r.b.w == kSprite) return glm::vec3(r.a);
  if (r.b.w == kLine) return glm::vec3(r.c);
  return (glm::vec3(r.a) + glm::vec3(r.b) + glm::vec3(r.c)) / 3.0f;
}

}  // namespace

Result<std::unique_ptr<EffectsPass>> EffectsPass::create(const Device& device, const Formats& formats,
                                                         vk::DescriptorSetLayout frameLayout) {
  std::unique_ptr<EffectsPass> pass(new EffectsPass(device));
  try {
    using Stage = vk::ShaderStageFlagBits;
    const auto stages = vk::ShaderStageFlags(Stage::eVertex | Stage::eFragment);
    pass->layout_ = makeSetLayout(device, {{vk::DescriptorType::eStorageBuffer, vk::ShaderStageFlags(Stage::eVertex)}});
    pass->pool_ = makeDescriptorPool(device, 1, {{vk::DescriptorType::eStorageBuffer, 1}});
    pass->set_ = allocateSet(device, pass->pool_, pass->layout_);
    const bool depth = formats.depth != vk::Format::eUndefined;
    pass->pipeline_ =
        makeGraphicsPipeline(device, GraphicsPipelineSettings{.vertexShader = "effects.vert",
                                                              .fragmentShader = "effects.frag",
                                                              .colorFormats = {formats.color},
                                                              .blend = Blend::kPremultipliedAlpha,
                                                              .depthFormat = formats.depth,
                                                              .depthTest = depth,
                                                              .depthWrite = false,
                                                              .samples = formats.samples,
                                                              .setLayouts = {frameLayout, *pass->layout_},
                                                              .pushConstants = {{stages, 0, sizeof(glm::vec4)}}});
  } catch (const std::exception& error) {
    return fail(std::string("effects: creating the pass failed: ") + error.what());
  }
  return pass;
}

Result<void> EffectsPass::prepare(const FrameInput& frame, std::uint32_t height) {
  if (auto valid = validate(frame.effects); !valid) return valid;
  std::vector<Record> unsorted = records(frame.effects);
  // Far to near, ties in the order given: the blend of what overlaps does not depend on the sort.
  const glm::vec3 eye = frame.camera.position;
  std::vector<float> distances(unsorted.size());
  for (std::size_t i = 0; i < unsorted.size(); ++i) {
    const glm::vec3 d = middle(unsorted[i]) - eye;
    distances[i] = glm::dot(d, d);
  }
  std::vector<std::size_t> order(unsorted.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::ranges::stable_sort(order, [&distances](std::size_t a, std::size_t b) { return distances[a] > distances[b]; });
  pixelAngle_ = 2.0f * std::tan(0.5f * frame.camera.verticalFovRadians) / float(std::max(height, 1u));
  count_ = 0;
  if (order.empty()) return {};
  const vk::DeviceSize bytes = order.size() * sizeof(Record);
  // The renderer waits for each frame before it prepares the next, so the buffer and its
  // descriptor are free to be replaced here.
  if (records_.size() < bytes) {
    try {
      records_ = Buffer(*device_, std::bit_ceil(bytes), vk::BufferUsageFlagBits::eStorageBuffer,
                        vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent);
    } catch (const std::exception& error) {
      return fail(std::string("effects: allocating room for ") + std::to_string(order.size()) +
                  " effects failed: " + error.what());
    }
    writeStorageBuffer(*device_, set_, 0, records_);
  }
  auto* out = reinterpret_cast<Record*>(records_.mapped().data());
  for (std::size_t i = 0; i < order.size(); ++i) out[i] = unsorted[order[i]];
  count_ = static_cast<std::uint32_t>(order.size());
  return {};
}

void EffectsPass::draw(const vk::raii::CommandBuffer& commands, const vk::raii::DescriptorSet& frameSet,
                       vk::Extent2D extent) const {
  if (count_ == 0) return;
  setViewportAndScissor(commands, extent);
  commands.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eGraphics, *pipeline_.layout, 0, {*frameSet, *set_}, {});
  commands.pushConstants<glm::vec4>(*pipeline_.layout,
                                    vk::ShaderStageFlagBits::eVertex | vk::ShaderStageFlagBits::eFragment, 0,
                                    glm::vec4(pixelAngle_, 0.0f, 0.0f, 0.0f));
  commands.draw(count_ * kVerticesPerRecord, 1, 0, 0);
}

}  // namespace mane::render
