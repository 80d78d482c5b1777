#include "scenes/gltf_loader.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "scenes/detail/gltf_access.hpp"

namespace mane::scenes {
namespace {

using Context = detail::GltfContext;
using detail::readFloats;
using detail::readIndices;

// Nodes nest at most this deep; deeper means a hostile file (the recursion needs a bound).
constexpr int kMaxNodeDepth = 256;

std::string modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS (0)";
    case TINYGLTF_MODE_LINE: return "LINES (1)";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP (2)";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP (3)";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP (5)";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN (6)";
    default: return "unknown mode " + std::to_string(mode);
  }
}

/// Appends one primitive, transformed to world space, to `out`.
Result<void> appendPrimitive(const Context& ctx, const tinygltf::Primitive& primitive, const std::string& where,
                             const glm::mat4& world, Mesh& out, std::vector<bool>& hasUv) {
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES) {
    return ctx.error(where + " uses primitive mode " + modeName(mode) + "; only TRIANGLES (4) is supported");
  }
  const auto positionIt = primitive.attributes.find("POSITION");
  if (positionIt == primitive.attributes.end()) {
    return ctx.error(where + " has no POSITION attribute");
  }
  auto positions = readFloats(ctx, positionIt->second, 3, where + " POSITION");
  if (!positions) return std::unexpected(positions.error());
  const std::size_t vertexCount = positions->size() / 3;

  std::vector<float> normals;
  if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end()) {
    auto read = readFloats(ctx, it->second, 3, where + " NORMAL");
    if (!read) return std::unexpected(read.error());
    normals = std::move(*read);
  }
  std::vector<float> uvs;
  if (auto it = primitive.attributes.find("TEXCOORD_0"); it != primitive.attributes.end()) {
    auto read = readFloats(ctx, it->second, 2, where + " TEXCOORD_0");
    if (!read) return std::unexpected(read.error());
    uvs = std::move(*read);
  }
  if ((!normals.empty() && normals.size() / 3 != vertexCount) || (!uvs.empty() && uvs.size() / 2 != vertexCount)) {
    return ctx.error(where + " has attributes of different lengths (POSITION has " + std::to_string(vertexCount) +
                     " elements)");
  }

  std::vector<std::uint32_t> indices;
  if (primitive.indices >= 0) {
    auto read = readIndices(ctx, primitive.indices, where + " indices");
    if (!read) return std::unexpected(read.error());
    indices = std::move(*read);
  } else {
    indices.resize(vertexCount);
    for (std::size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<std::uint32_t>(i);
  }
  if (indices.size() % 3 != 0) {
    return ctx.error(where + " has " + std::to_string(indices.size()) + " indices, which is not a multiple of 3");
  }
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertexCount) {
      return ctx.error(where + " index " + std::to_string(i) + " is " + std::to_string(indices[i]) +
                       " but the primitive has only " + std::to_string(vertexCount) + " vertices");
    }
  }

  Mesh part;
  part.positions.resize(vertexCount);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    part.positions[v] = glm::vec3(world * glm::vec4(glm::make_vec3(&(*positions)[3 * v]), 1.0f));
  }
  // A mirroring transform flips the triangles' facing; swap two corners to keep it.
  const glm::mat3 linear(world);
  const bool mirrored = glm::determinant(linear) < 0.0f;
  if (mirrored) {
    for (std::size_t t = 0; t < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);
  }
  part.indices = std::move(indices);
  if (normals.empty()) {
    computeSmoothNormals(part);
  } else {
    // Normals transform by the inverse transpose so non-uniform scale keeps them normal.
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
    part.normals.resize(vertexCount);
    for (std::size_t v = 0; v < vertexCount; ++v) {
      const glm::vec3 n = normalMatrix * glm::make_vec3(&normals[3 * v]);
      const float length = glm::length(n);
      part.normals[v] = length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
    }
  }

  const auto base = static_cast<std::uint32_t>(out.positions.size());
  out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
  out.normals.insert(out.normals.end(), part.normals.begin(), part.normals.end());
  for (std::size_t v = 0; v < vertexCount; ++v) {
    out.uvs.push_back(uvs.empty() ? glm::vec2(0.0f) : glm::make_vec2(&uvs[2 * v]));
    hasUv.push_back(!uvs.empty());
  }
  for (std::uint32_t i : part.indices) out.indices.push_back(base + i);
  return {};
}

/// Appends the meshes of `nodeIndex` and its descendants. `visited` marks nodes seen so far:
/// glTF nodes form disjoint trees (glTF 2.0 §3.5.1), so a second visit means a node with two
/// parents or a cycle, which would otherwise multiply the work exponentially or never end.
Result<void> visitNode(const Context& ctx, int nodeIndex, const glm::mat4& parent, int depth,
                       std::vector<bool>& visited, Mesh& out, std::vector<bool>& hasUv) {
  const auto& nodes = ctx.model.nodes;
  if (nodeIndex < 0 || static_cast<std::size_t>(nodeIndex) >= nodes.size()) {
    return ctx.error("the scene refers to node " + std::to_string(nodeIndex) + ", but the file has " +
                     std::to_string(nodes.size()) + " nodes");
  }
  if (visited[static_cast<std::size_t>(nodeIndex)]) {
    return ctx.error("node " + std::to_string(nodeIndex) +
                     " is reached twice: glTF nodes must form trees (a node with two parents, "
                     "a cycle, or a scene listing a child node as a root)");
  }
  visited[static_cast<std::size_t>(nodeIndex)] = true;
  if (depth > kMaxNodeDepth) {
    return ctx.error("node " + std::to_string(nodeIndex) + " is nested more than " + std::to_string(kMaxNodeDepth) +
                     " levels deep");
  }
  const tinygltf::Node& node = nodes[static_cast<std::size_t>(nodeIndex)];
  const glm::mat4 world = parent * detail::nodeLocalMatrix(node);
  if (node.mesh >= 0) {
    if (static_cast<std::size_t>(node.mesh) >= ctx.model.meshes.size()) {
      return ctx.error("node " + std::to_string(nodeIndex) + " refers to missing mesh " + std::to_string(node.mesh));
    }
    const tinygltf::Mesh& mesh = ctx.model.meshes[static_cast<std::size_t>(node.mesh)];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where =
          "mesh " + std::to_string(node.mesh) + " ('" + mesh.name + "') primitive " + std::to_string(p);
      if (auto ok = appendPrimitive(ctx, mesh.primitives[p], where, world, out, hasUv); !ok) {
        return ok;
      }
    }
  }
  for (int child : node.children) {
    if (auto ok = visitNode(ctx, child, world, depth + 1, visited, out, hasUv); !ok) return ok;
  }
  return {};
}

}  // namespace

Result<Mesh> loadGltf(const std::filesystem::path& file) {
  auto model = detail::parseGltfFile(file);
  if (!model) return std::unexpected(model.error());
  const Context ctx{*model, file.string()};
  Mesh mesh;
  mesh.name = file.stem().string();
  std::vector<bool> hasUv;
  auto roots = detail::defaultSceneRoots(ctx);
  if (!roots) return std::unexpected(roots.error());
  std::vector<bool> visited(model->nodes.size(), false);
  for (int root : *roots) {
    if (auto ok = visitNode(ctx, root, glm::mat4(1.0f), 0, visited, mesh, hasUv); !ok) {
      return std::unexpected(ok.error());
    }
  }
  if (mesh.indices.empty()) {
    return ctx.error("the default scene has no triangles");
  }
  if (std::find(hasUv.begin(), hasUv.end(), true) == hasUv.end()) mesh.uvs.clear();
  return mesh;
}

}  // namespace mane::scenes
