#include "render/passes/skin_diffusion_mesh.hpp"

#include <cmath>
#include <cstddef>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "render/descriptors.hpp"
#include "render/passes/skin_uv_seams.hpp"

namespace mane::render {
namespace {

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(glm::vec2 v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}

Result<void> validate(const MeshData& mesh) {
  const std::size_t count = mesh.positions.size();
  if (mesh.indices.empty()) return fail("skin diffusion mesh: it has no triangles (indices is empty)");
  if (mesh.indices.size() % 3 != 0)
    return fail("skin diffusion mesh: indices has " + std::to_string(mesh.indices.size()) +
                " entries, expected a multiple of 3 (a triangle list)");
  if (mesh.normals.size() != count)
    return fail("skin diffusion mesh: normals has " + std::to_string(mesh.normals.size()) +
                " entries, expected one per position (" + std::to_string(count) + ")");
  if (mesh.uvs.size() != count)
    return fail("skin diffusion mesh: uvs has " + std::to_string(mesh.uvs.size()) +
                " entries, expected one per position (" + std::to_string(count) +
                "): texture-space diffusion draws the mesh at its uvs");
  for (std::size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= count)
      return fail("skin diffusion mesh: indices[" + std::to_string(i) + "] is " + std::to_string(mesh.indices[i]) +
                  ", past the " + std::to_string(count) + " positions");
  for (std::size_t i = 0; i < count; ++i) {
    if (!finite(mesh.positions[i]))
      return fail("skin diffusion mesh: positions[" + std::to_string(i) + "] is not finite");
    if (!finite(mesh.normals[i])) return fail("skin diffusion mesh: normals[" + std::to_string(i) + "] is not finite");
    if (!finite(mesh.uvs[i])) return fail("skin diffusion mesh: uvs[" + std::to_string(i) + "] is not finite");
  }
  return {};
}

// sqrt(Σ world area / Σ uv area), or nothing when no triangle has an area in uv space.
std::optional<double> meanUvScale(const MeshData& mesh) {
  double world = 0.0, uv = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const glm::dvec3 e1 = glm::dvec3(mesh.positions[b]) - glm::dvec3(mesh.positions[a]);
    const glm::dvec3 e2 = glm::dvec3(mesh.positions[c]) - glm::dvec3(mesh.positions[a]);
    const glm::dvec2 f1 = glm::dvec2(mesh.uvs[b]) - glm::dvec2(mesh.uvs[a]);
    const glm::dvec2 f2 = glm::dvec2(mesh.uvs[c]) - glm::dvec2(mesh.uvs[a]);
    world += 0.5 * glm::length(glm::cross(e1, e2));
    uv += 0.5 * std::abs(f1.x * f2.y - f1.y * f2.x);
  }
  if (!(uv > 0.0) || !(world > 0.0)) return std::nullopt;
  return std::sqrt(world / uv);
}

}  // namespace

Result<SkinDiffusionMesh> SkinDiffusionMesh::create(const Device& device, const MeshData& mesh, float seamReach) {
  if (!(seamReach >= 0.0f && seamReach <= 0.25f))
    return fail("skin diffusion mesh: the seam reach is " + std::to_string(seamReach) +
                " uv units, expected 0 to 0.25 (a quarter of the map)");
  if (auto valid = validate(mesh); !valid) return std::unexpected(valid.error());
  const std::optional<double> scale = meanUvScale(mesh);
  if (!scale) return fail("skin diffusion mesh: no triangle has an area both in space and in uv space");
  std::vector<SkinDiffusionVertex> vertices(mesh.positions.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) vertices[i] = {mesh.positions[i], mesh.normals[i], mesh.uvs[i]};
  const std::vector<SkinDrawVertex> draw = textureSpaceDrawList(mesh.positions, mesh.uvs, mesh.indices, seamReach);
  SkinDiffusionMesh result;
  try {
    result.vertices_ =
        Buffer::withData(device, std::as_bytes(std::span(vertices)), vk::BufferUsageFlagBits::eStorageBuffer);
    result.drawList_ = Buffer::withData(device, std::as_bytes(std::span(draw)), vk::BufferUsageFlagBits::eVertexBuffer);
    auto descriptors = std::make_unique<Descriptors>();
    descriptors->layout = makeVerticesLayout(device);
    descriptors->pool = makeDescriptorPool(device, 1, {{vk::DescriptorType::eStorageBuffer, 1}});
    descriptors->set = allocateSet(device, descriptors->pool, descriptors->layout);
    writeStorageBuffer(device, descriptors->set, 0, result.vertices_);
    result.descriptors_ = std::move(descriptors);
  } catch (const std::exception& error) {
    return fail(std::string("skin diffusion mesh: uploading failed: ") + error.what());
  }
  result.drawCount_ = static_cast<std::uint32_t>(draw.size());
  result.uvScale_ = *scale;
  return result;
}

vk::raii::DescriptorSetLayout SkinDiffusionMesh::makeVerticesLayout(const Device& device) {
  return makeSetLayout(device, {{vk::DescriptorType::eStorageBuffer, vk::ShaderStageFlagBits::eVertex}});
}

SkinnedVertexTarget SkinDiffusionMesh::vertexTarget() const {
  constexpr auto floats = [](std::size_t bytes) { return static_cast<std::uint32_t>(bytes / sizeof(float)); };
  return {.buffer = &vertices_,
          .stride = floats(sizeof(SkinDiffusionVertex)),
          .positionOffset = floats(offsetof(SkinDiffusionVertex, position)),
          .normalOffset = floats(offsetof(SkinDiffusionVertex, normal))};
}

}  // namespace mane::render
