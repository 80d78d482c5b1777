#include "scenes/detail/gltf_character_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "scenes/mesh.hpp"

namespace mane::scenes::detail {
namespace {

/// A primitive as read, before merging into its mesh's surface.
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
  std::vector<std::uint32_t> indices;
  std::size_t influenceSets = 0;  ///< JOINTS_n/WEIGHTS_n pairs; 4 influences each
  std::vector<std::uint32_t> joints;
  std::vector<float> weights;
  std::vector<physics::MorphTarget> targets;
};

bool allFinite(const std::vector<float>& values) {
  return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

std::string meshLabel(const tinygltf::Model& model, int meshIndex) {
  const std::string& name = model.meshes[static_cast<std::size_t>(meshIndex)].name;
  return "mesh " + std::to_string(meshIndex) + (name.empty() ? "" : " ('" + name + "')");
}

std::string nodeLabel(const tinygltf::Model& model, int nodeIndex) {
  const std::string& name = model.nodes[static_cast<std::size_t>(nodeIndex)].name;
  return "node " + std::to_string(nodeIndex) + (name.empty() ? "" : " ('" + name + "')");
}

/// `readVec3s` takes any element count when given this.
constexpr std::size_t kAnyCount = ~std::size_t(0);

/// A VEC3 attribute of `expectedCount` (or, with kAnyCount, any number of) finite elements.
Result<std::vector<glm::vec3>> readVec3s(const GltfContext& ctx, int accessor, std::size_t expectedCount,
                                         const std::string& role) {
  auto floats = readFloats(ctx, accessor, 3, role);
  if (!floats) return std::unexpected(floats.error());
  if (expectedCount == kAnyCount) expectedCount = floats->size() / 3;
  if (floats->size() / 3 != expectedCount) {
    return ctx.error(role + " has " + std::to_string(floats->size() / 3) + " elements; the primitive has " +
                     std::to_string(expectedCount) + " vertices");
  }
  if (!allFinite(*floats)) return ctx.error(role + " holds a NaN or infinite value");
  std::vector<glm::vec3> out(expectedCount);
  for (std::size_t i = 0; i < expectedCount; ++i) out[i] = glm::make_vec3(&(*floats)[3 * i]);
  return out;
}

/// Joint influences of one skinned primitive: every JOINTS_n/WEIGHTS_n pair, checked per vertex.
Result<void> readInfluences(const GltfContext& ctx, const tinygltf::Primitive& primitive, const std::string& where,
                            const CharacterSkin& skin, int skinIndex, Primitive& out) {
  const std::size_t vertices = out.positions.size();
  std::vector<std::vector<std::uint32_t>> jointSets;
  std::vector<std::vector<float>> weightSets;
  for (std::size_t set = 0;; ++set) {
    const std::string jointsName = "JOINTS_" + std::to_string(set);
    const std::string weightsName = "WEIGHTS_" + std::to_string(set);
    const auto joints = primitive.attributes.find(jointsName);
    const auto weights = primitive.attributes.find(weightsName);
    const bool hasJoints = joints != primitive.attributes.end();
    const bool hasWeights = weights != primitive.attributes.end();
    if (!hasJoints && !hasWeights) break;
    if (hasJoints != hasWeights) {
      return ctx.error(where + " has " + (hasJoints ? jointsName : weightsName) + " without " +
                       (hasJoints ? weightsName : jointsName));
    }
    auto jointValues = readUnsigned(ctx, joints->second, 4, where + " " + jointsName);
    if (!jointValues) return std::unexpected(jointValues.error());
    auto weightValues = readFloats(ctx, weights->second, 4, where + " " + weightsName);
    if (!weightValues) return std::unexpected(weightValues.error());
    if (jointValues->size() != 4 * vertices || weightValues->size() != 4 * vertices) {
      return ctx.error(where + " has " + std::to_string(jointValues->size() / 4) + " " + jointsName + " and " +
                       std::to_string(weightValues->size() / 4) + " " + weightsName + " elements for " +
                       std::to_string(vertices) + " vertices");
    }
    jointSets.push_back(std::move(*jointValues));
    weightSets.push_back(std::move(*weightValues));
  }
  if (jointSets.empty()) {
    return ctx.error(where + " is bound to skin " + std::to_string(skinIndex) +
                     " but has no JOINTS_0 and WEIGHTS_0 attributes");
  }
  const std::size_t sets = jointSets.size();
  const std::size_t perVertex = 4 * sets;
  out.influenceSets = sets;
  out.joints.resize(vertices * perVertex);
  out.weights.resize(vertices * perVertex);
  for (std::size_t v = 0; v < vertices; ++v) {
    float sum = 0.0f;
    for (std::size_t set = 0; set < sets; ++set) {
      for (std::size_t i = 0; i < 4; ++i) {
        const std::uint32_t joint = jointSets[set][4 * v + i];
        const float weight = weightSets[set][4 * v + i];
        if (joint >= skin.joints.size()) {
          return ctx.error(where + " vertex " + std::to_string(v) + " JOINTS_" + std::to_string(set) + " names joint " +
                           std::to_string(joint) + ", but skin " + std::to_string(skinIndex) + " has " +
                           std::to_string(skin.joints.size()) + " joints");
        }
        if (!std::isfinite(weight) || weight < 0.0f) {
          return ctx.error(where + " vertex " + std::to_string(v) + " WEIGHTS_" + std::to_string(set) +
                           " holds weight " + std::to_string(weight) + "; weights must be finite and >= 0");
        }
        out.joints[v * perVertex + 4 * set + i] = joint;
        out.weights[v * perVertex + 4 * set + i] = weight;
        sum += weight;
      }
    }
    if (!(sum > 0.0f) || !std::isfinite(sum)) {
      return ctx.error(where + " vertex " + std::to_string(v) + " has joint weights that sum to " +
                       std::to_string(sum) + "; a skinned vertex needs a positive total weight");
    }
  }
  return {};
}

Result<Primitive> readPrimitive(const GltfContext& ctx, const tinygltf::Primitive& primitive, const std::string& where,
                                const std::vector<CharacterSkin>& skins, int skinIndex) {
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES) {
    return ctx.error(where + " uses primitive mode " + std::to_string(mode) + "; only TRIANGLES (4) is supported");
  }
  const auto position = primitive.attributes.find("POSITION");
  if (position == primitive.attributes.end()) return ctx.error(where + " has no POSITION attribute");
  Primitive out;
  {
    auto positions = readVec3s(ctx, position->second, kAnyCount, where + " POSITION");
    if (!positions) return std::unexpected(positions.error());
    out.positions = std::move(*positions);
  }
  const std::size_t vertices = out.positions.size();
  if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end()) {
    auto normals = readVec3s(ctx, it->second, vertices, where + " NORMAL");
    if (!normals) return std::unexpected(normals.error());
    out.normals = std::move(*normals);
  }
  if (auto it = primitive.attributes.find("TANGENT"); it != primitive.attributes.end()) {
    auto floats = readFloats(ctx, it->second, 4, where + " TANGENT");
    if (!floats) return std::unexpected(floats.error());
    if (floats->size() / 4 != vertices || !allFinite(*floats)) {
      return ctx.error(where + " TANGENT needs " + std::to_string(vertices) + " finite elements; it has " +
                       std::to_string(floats->size() / 4));
    }
    out.tangents.resize(vertices);
    for (std::size_t v = 0; v < vertices; ++v) out.tangents[v] = glm::make_vec4(&(*floats)[4 * v]);
  }

  if (primitive.indices >= 0) {
    auto indices = readIndices(ctx, primitive.indices, where + " indices");
    if (!indices) return std::unexpected(indices.error());
    out.indices = std::move(*indices);
  } else {
    out.indices.resize(vertices);
    for (std::size_t v = 0; v < vertices; ++v) out.indices[v] = static_cast<std::uint32_t>(v);
  }
  if (out.indices.size() % 3 != 0) {
    return ctx.error(where + " has " + std::to_string(out.indices.size()) + " indices, not a multiple of 3");
  }
  for (std::size_t i = 0; i < out.indices.size(); ++i) {
    if (out.indices[i] >= vertices) {
      return ctx.error(where + " index " + std::to_string(i) + " is " + std::to_string(out.indices[i]) +
                       " but the primitive has only " + std::to_string(vertices) + " vertices");
    }
  }

  if (skinIndex >= 0) {
    if (auto ok = readInfluences(ctx, primitive, where, skins[static_cast<std::size_t>(skinIndex)], skinIndex, out);
        !ok) {
      return std::unexpected(ok.error());
    }
  }

  for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
    physics::MorphTarget target;
    const std::string targetWhere = where + " morph target " + std::to_string(t);
    const auto& attributes = primitive.targets[t];
    const std::pair<const char*, std::vector<glm::vec3>*> readable[] = {
        {"POSITION", &target.positionDeltas}, {"NORMAL", &target.normalDeltas}, {"TANGENT", &target.tangentDeltas}};
    for (const auto& [attribute, deltas] : readable) {
      if (auto it = attributes.find(attribute); it != attributes.end()) {
        auto read = readVec3s(ctx, it->second, vertices, targetWhere + " " + attribute);
        if (!read) return std::unexpected(read.error());
        *deltas = std::move(*read);
      }
    }
    out.targets.push_back(std::move(target));
  }
  return out;
}

/// Smooth normals for a primitive the file gives none (the same rule as the bind-pose loader).
std::vector<glm::vec3> smoothNormals(const Primitive& primitive) {
  Mesh mesh;
  mesh.positions = primitive.positions;
  mesh.indices = primitive.indices;
  computeSmoothNormals(mesh);
  return std::move(mesh.normals);
}

/// A morph target's deltas of one attribute over the merged surface: empty when no primitive
/// has them, zeros for the primitives that lack them.
void appendDeltas(std::vector<glm::vec3>& merged, const std::vector<glm::vec3>& part, std::size_t mergedBefore,
                  std::size_t partVertices) {
  if (part.empty() && merged.empty()) return;
  merged.resize(mergedBefore, glm::vec3(0.0f));
  if (part.empty()) {
    merged.resize(mergedBefore + partVertices, glm::vec3(0.0f));
  } else {
    merged.insert(merged.end(), part.begin(), part.end());
  }
}

Result<std::vector<std::string>> targetNames(const GltfContext& ctx, const tinygltf::Mesh& mesh,
                                             const std::string& where, std::size_t targets) {
  std::vector<std::string> names(targets);
  if (!mesh.extras.IsObject() || !mesh.extras.Has("targetNames")) return names;
  const tinygltf::Value& list = mesh.extras.Get("targetNames");
  if (!list.IsArray() || list.ArrayLen() != targets) {
    return ctx.error(where + " extras.targetNames must be an array of " + std::to_string(targets) +
                     " names, one per morph target");
  }
  for (std::size_t t = 0; t < targets; ++t) {
    const tinygltf::Value& name = list.Get(static_cast<int>(t));
    if (!name.IsString()) return ctx.error(where + " extras.targetNames[" + std::to_string(t) + "] is not a string");
    names[t] = name.Get<std::string>();
  }
  return names;
}

}  // namespace

Result<std::vector<CharacterSkin>> readSkins(const GltfContext& ctx) {
  std::vector<CharacterSkin> skins;
  const auto& model = ctx.model;
  for (std::size_t s = 0; s < model.skins.size(); ++s) {
    const tinygltf::Skin& skin = model.skins[s];
    const std::string where = "skin " + std::to_string(s) + (skin.name.empty() ? "" : " ('" + skin.name + "')");
    CharacterSkin out;
    out.name = skin.name;
    if (skin.joints.empty()) return ctx.error(where + " has no joints");
    for (int joint : skin.joints) {
      if (joint < 0 || static_cast<std::size_t>(joint) >= model.nodes.size()) {
        return ctx.error(where + " names joint node " + std::to_string(joint) + ", but the file has " +
                         std::to_string(model.nodes.size()) + " nodes");
      }
    }
    if (skin.skeleton < -1 || skin.skeleton >= static_cast<int>(model.nodes.size())) {
      return ctx.error(where + " names skeleton root node " + std::to_string(skin.skeleton) +
                       ", which is not in the file");
    }
    out.joints = skin.joints;
    if (skin.inverseBindMatrices < 0) {
      out.inverseBindMatrices.assign(out.joints.size(), glm::mat4(1.0f));
    } else {
      const std::string role = where + " inverseBindMatrices";
      const int index = skin.inverseBindMatrices;
      if (static_cast<std::size_t>(index) < model.accessors.size() &&
          model.accessors[static_cast<std::size_t>(index)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        return ctx.error(role + " (accessor " + std::to_string(index) + ") must hold floats");
      }
      auto floats = readFloats(ctx, index, 16, role);
      if (!floats) return std::unexpected(floats.error());
      if (floats->size() / 16 < out.joints.size()) {
        return ctx.error(role + " (accessor " + std::to_string(index) + ") holds " +
                         std::to_string(floats->size() / 16) + " matrices for " + std::to_string(out.joints.size()) +
                         " joints");
      }
      if (!allFinite(*floats)) {
        return ctx.error(role + " (accessor " + std::to_string(index) + ") holds a NaN or infinite value");
      }
      for (std::size_t j = 0; j < out.joints.size(); ++j) {
        out.inverseBindMatrices.push_back(glm::make_mat4(&(*floats)[16 * j]));
      }
    }
    skins.push_back(std::move(out));
  }
  return skins;
}

Result<std::vector<float>> restMorphWeights(const GltfContext& ctx, int nodeIndex) {
  const tinygltf::Node& node = ctx.model.nodes[static_cast<std::size_t>(nodeIndex)];
  if (node.mesh < 0) return std::vector<float>{};
  if (static_cast<std::size_t>(node.mesh) >= ctx.model.meshes.size()) {
    return ctx.error(nodeLabel(ctx.model, nodeIndex) + " refers to missing mesh " + std::to_string(node.mesh));
  }
  const tinygltf::Mesh& mesh = ctx.model.meshes[static_cast<std::size_t>(node.mesh)];
  const std::size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives.front().targets.size();
  const auto check = [&](const std::vector<double>& weights, const std::string& owner) -> Result<std::vector<float>> {
    if (weights.size() != targets) {
      return ctx.error(owner + " has " + std::to_string(weights.size()) + " morph weights for " +
                       std::to_string(targets) + " morph targets");
    }
    std::vector<float> out;
    for (double w : weights) {
      if (!std::isfinite(w)) return ctx.error(owner + " has a NaN or infinite morph weight");
      out.push_back(static_cast<float>(w));
    }
    return out;
  };
  if (!node.weights.empty()) return check(node.weights, nodeLabel(ctx.model, nodeIndex));
  if (!mesh.weights.empty()) return check(mesh.weights, meshLabel(ctx.model, node.mesh));
  return std::vector<float>(targets, 0.0f);
}

Result<CharacterMesh> readCharacterMesh(const GltfContext& ctx, int nodeIndex,
                                        const std::vector<CharacterSkin>& skins) {
  const tinygltf::Model& model = ctx.model;
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(nodeIndex)];
  if (node.mesh < 0 || static_cast<std::size_t>(node.mesh) >= model.meshes.size()) {
    return ctx.error(nodeLabel(model, nodeIndex) + " refers to missing mesh " + std::to_string(node.mesh));
  }
  if (node.skin < -1 || node.skin >= static_cast<int>(skins.size())) {
    return ctx.error(nodeLabel(model, nodeIndex) + " refers to missing skin " + std::to_string(node.skin));
  }
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
  const std::string meshWhere = meshLabel(model, node.mesh);
  if (mesh.primitives.empty()) return ctx.error(meshWhere + " has no primitives");

  std::vector<Primitive> primitives;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const std::string where = meshWhere + " primitive " + std::to_string(p);
    auto primitive = readPrimitive(ctx, mesh.primitives[p], where, skins, node.skin);
    if (!primitive) return std::unexpected(primitive.error());
    if (primitive->targets.size() != mesh.primitives.front().targets.size()) {
      return ctx.error(where + " has " + std::to_string(primitive->targets.size()) +
                       " morph targets, primitive 0 has " + std::to_string(mesh.primitives.front().targets.size()) +
                       "; every primitive of a mesh must have the same targets");
    }
    primitives.push_back(std::move(*primitive));
  }
  const std::size_t targetCount = primitives.front().targets.size();

  CharacterMesh out;
  out.name = mesh.name;
  out.mesh = node.mesh;
  out.node = nodeIndex;
  out.skin = node.skin;
  auto names = targetNames(ctx, mesh, meshWhere, targetCount);
  if (!names) return std::unexpected(names.error());
  out.morphTargetNames = std::move(*names);

  physics::SkinnedMeshData data;
  const bool tangents =
      std::all_of(primitives.begin(), primitives.end(), [](const Primitive& p) { return !p.tangents.empty(); });
  std::size_t sets = 0;
  for (const Primitive& p : primitives) sets = std::max(sets, p.influenceSets);
  data.influencesPerVertex = node.skin >= 0 ? 4 * sets : 1;
  data.jointCount = node.skin >= 0 ? skins[static_cast<std::size_t>(node.skin)].joints.size() : 1;
  data.morphTargets.resize(targetCount);
  for (std::size_t t = 0; t < targetCount; ++t) data.morphTargets[t].name = out.morphTargetNames[t];

  for (const tinygltf::Primitive& primitive : mesh.primitives) {
    const bool named = primitive.material >= 0 && static_cast<std::size_t>(primitive.material) < model.materials.size();
    out.primitiveMaterials.push_back(named ? model.materials[static_cast<std::size_t>(primitive.material)].name : "");
  }
  for (Primitive& p : primitives) {
    const std::size_t before = data.positions.size();
    const std::size_t count = p.positions.size();
    out.primitiveFirstVertex.push_back(before);
    out.primitiveFirstIndex.push_back(data.indices.size());
    for (std::uint32_t index : p.indices) data.indices.push_back(static_cast<std::uint32_t>(before) + index);
    data.positions.insert(data.positions.end(), p.positions.begin(), p.positions.end());
    const std::vector<glm::vec3> normals = p.normals.empty() ? smoothNormals(p) : std::move(p.normals);
    data.normals.insert(data.normals.end(), normals.begin(), normals.end());
    if (tangents) data.tangents.insert(data.tangents.end(), p.tangents.begin(), p.tangents.end());
    if (node.skin >= 0) {
      // Pad primitives with fewer influence sets by joint 0 at weight 0.
      const std::size_t own = 4 * p.influenceSets;
      for (std::size_t v = 0; v < count; ++v) {
        for (std::size_t i = 0; i < data.influencesPerVertex; ++i) {
          data.joints.push_back(i < own ? p.joints[v * own + i] : 0u);
          data.weights.push_back(i < own ? p.weights[v * own + i] : 0.0f);
        }
      }
    } else {
      data.joints.insert(data.joints.end(), count, 0u);
      data.weights.insert(data.weights.end(), count, 1.0f);
    }
    for (std::size_t t = 0; t < targetCount; ++t) {
      physics::MorphTarget& merged = data.morphTargets[t];
      appendDeltas(merged.positionDeltas, p.targets[t].positionDeltas, before, count);
      appendDeltas(merged.normalDeltas, p.targets[t].normalDeltas, before, count);
      appendDeltas(merged.tangentDeltas, p.targets[t].tangentDeltas, before, count);
    }
  }
  // A target attribute that only an earlier primitive had still needs zeros for the later ones.
  for (physics::MorphTarget& target : data.morphTargets) {
    for (auto* deltas : {&target.positionDeltas, &target.normalDeltas, &target.tangentDeltas}) {
      if (!deltas->empty()) deltas->resize(data.positions.size(), glm::vec3(0.0f));
    }
  }

  auto surface = physics::SkinnedMesh::create(std::move(data));
  if (!surface) return ctx.error(meshWhere + ": " + surface.error().message);
  out.surface = std::move(*surface);
  return out;
}

}  // namespace mane::scenes::detail
