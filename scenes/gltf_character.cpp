#include "scenes/gltf_character.hpp"

#include <utility>

#include "scenes/detail/gltf_access.hpp"
#include "scenes/detail/gltf_character_clips.hpp"
#include "scenes/detail/gltf_character_meshes.hpp"

namespace mane::scenes {
namespace {

using detail::GltfContext;

std::string quotedList(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "'" : ", '") + name + "'";
  return list;
}

/// Every node of the file as a skeleton node: parents from the children lists (each node at
/// most one parent), rest TRS or fixed matrix, rest morph weights.
Result<physics::Skeleton> readSkeleton(const GltfContext& ctx) {
  const auto& nodes = ctx.model.nodes;
  std::vector<physics::SkeletonNode> skeleton(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (int child : nodes[i].children) {
      if (child < 0 || static_cast<std::size_t>(child) >= nodes.size()) {
        return ctx.error("node " + std::to_string(i) + " has child " + std::to_string(child) + ", but the file has " +
                         std::to_string(nodes.size()) + " nodes");
      }
      physics::SkeletonNode& below = skeleton[static_cast<std::size_t>(child)];
      if (below.parent >= 0 || child == static_cast<int>(i)) {
        return ctx.error("node " + std::to_string(child) +
                         " has two parents or is its own child: glTF nodes must form trees");
      }
      below.parent = static_cast<int>(i);
    }
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const tinygltf::Node& node = nodes[i];
    physics::SkeletonNode& out = skeleton[i];
    out.name = node.name;
    if (node.matrix.size() == 16) {
      out.fixedMatrix = detail::nodeLocalMatrix(node);
    } else {
      if (node.translation.size() == 3) {
        out.rest.translation =
            glm::vec3(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                      static_cast<float>(node.translation[2]));
      }
      if (node.rotation.size() == 4) {
        // glTF stores x, y, z, w; glm::quat's constructor takes w first.
        out.rest.rotation = glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                                      static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
      }
      if (node.scale.size() == 3) {
        out.rest.scale = glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                                   static_cast<float>(node.scale[2]));
      }
    }
    auto weights = detail::restMorphWeights(ctx, static_cast<int>(i));
    if (!weights) return std::unexpected(weights.error());
    out.restMorphWeights = std::move(*weights);
  }
  auto created = physics::Skeleton::create(std::move(skeleton));
  if (!created) return ctx.error(created.error().message);
  return created;
}

/// The mesh instances under the default scene's roots, parent first.
Result<std::vector<CharacterMesh>> readMeshes(const GltfContext& ctx, const physics::Skeleton& skeleton,
                                              const std::vector<CharacterSkin>& skins) {
  auto roots = detail::defaultSceneRoots(ctx);
  if (!roots) return std::unexpected(roots.error());
  std::vector<bool> isRoot(skeleton.nodeCount(), false);
  for (int root : *roots) {
    if (root < 0 || static_cast<std::size_t>(root) >= skeleton.nodeCount()) {
      return ctx.error("the scene refers to node " + std::to_string(root) + ", but the file has " +
                       std::to_string(skeleton.nodeCount()) + " nodes");
    }
    isRoot[static_cast<std::size_t>(root)] = true;
  }
  // A node is in the scene when it or an ancestor is one of the scene's roots; the parent-first
  // order settles the ancestors before the node.
  std::vector<bool> inScene(skeleton.nodeCount(), false);
  std::vector<CharacterMesh> meshes;
  for (int index : skeleton.parentFirstOrder()) {
    const auto i = static_cast<std::size_t>(index);
    const int parent = skeleton.nodes()[i].parent;
    inScene[i] = isRoot[i] || (parent >= 0 && inScene[static_cast<std::size_t>(parent)]);
    if (!inScene[i] || ctx.model.nodes[i].mesh < 0) continue;
    auto mesh = detail::readCharacterMesh(ctx, index, skins);
    if (!mesh) return std::unexpected(mesh.error());
    meshes.push_back(std::move(*mesh));
  }
  return meshes;
}

}  // namespace

Result<Character> loadCharacter(const std::filesystem::path& file) {
  auto model = detail::parseGltfFile(file);
  if (!model) return std::unexpected(model.error());
  const GltfContext ctx{*model, file.string()};

  Character character;
  character.file = file.string();
  auto skeleton = readSkeleton(ctx);
  if (!skeleton) return std::unexpected(skeleton.error());
  auto skins = detail::readSkins(ctx);
  if (!skins) return std::unexpected(skins.error());
  auto meshes = readMeshes(ctx, *skeleton, *skins);
  if (!meshes) return std::unexpected(meshes.error());
  auto clips = detail::readClips(ctx, *skeleton);
  if (!clips) return std::unexpected(clips.error());
  character.skeleton = std::move(*skeleton);
  character.skins = std::move(*skins);
  character.meshes = std::move(*meshes);
  character.clips = std::move(*clips);
  return character;
}

Result<const physics::AnimationClip*> Character::findClip(std::string_view name) const {
  std::vector<std::string> names;
  for (const physics::AnimationClip& clip : clips) {
    if (clip.name() == name) return &clip;
    names.push_back(clip.name());
  }
  return fail(file + ": no animation named '" + std::string(name) + "'; the file has " + quotedList(names));
}

Result<std::size_t> Character::findMesh(std::string_view name) const {
  std::vector<std::string> names;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (meshes[m].name == name) return m;
    names.push_back(meshes[m].name);
  }
  return fail(file + ": no mesh named '" + std::string(name) + "'; the file has " + quotedList(names));
}

Result<std::size_t> Character::findMorphTarget(std::size_t meshIndex, std::string_view name) const {
  if (meshIndex >= meshes.size()) {
    return fail(file + ": mesh index " + std::to_string(meshIndex) + " is past the " + std::to_string(meshes.size()) +
                " meshes");
  }
  const CharacterMesh& mesh = meshes[meshIndex];
  for (std::size_t t = 0; t < mesh.morphTargetNames.size(); ++t) {
    if (mesh.morphTargetNames[t] == name) return t;
  }
  return fail(file + ": mesh '" + mesh.name + "' has no morph target named '" + std::string(name) + "'; it has " +
              quotedList(mesh.morphTargetNames));
}

Result<std::vector<glm::mat4>> Character::jointMatrices(std::size_t meshIndex, std::span<const glm::mat4> world) const {
  if (meshIndex >= meshes.size()) {
    return fail(file + ": mesh index " + std::to_string(meshIndex) + " is past the " + std::to_string(meshes.size()) +
                " meshes");
  }
  if (world.size() != skeleton.nodeCount()) {
    return fail(file + ": joint matrices need one world matrix per node (" + std::to_string(skeleton.nodeCount()) +
                "); got " + std::to_string(world.size()));
  }
  const CharacterMesh& mesh = meshes[meshIndex];
  if (mesh.skin < 0) return std::vector<glm::mat4>{world[static_cast<std::size_t>(mesh.node)]};
  const CharacterSkin& skin = skins[static_cast<std::size_t>(mesh.skin)];
  std::vector<glm::mat4> matrices(skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    matrices[j] = world[static_cast<std::size_t>(skin.joints[j])] * skin.inverseBindMatrices[j];
  }
  return matrices;
}

}  // namespace mane::scenes
