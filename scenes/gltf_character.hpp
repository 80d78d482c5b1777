#pragma once
// A glTF 2.0 character (.gltf or .glb) as plain data: the node hierarchy, skins, meshes with
// their joint influences and morph targets, and animation clips. The physics types it holds
// (physics/skeleton.hpp, physics/animation_clip.hpp, physics/skinning.hpp) do the posing and
// deforming; this file only reads and checks.
//
// Every mesh becomes a skinned mesh so that one call deforms any of them into world space: a
// mesh with a skin is bound to the skin's joints (glTF ignores the transform of the node that
// holds a skinned mesh, §3.7.3.3), and a mesh without one is bound, with weight 1, to the node
// that holds it, whose world matrix is then its single joint matrix.

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>

#include "common/error.hpp"
#include "physics/animation_clip.hpp"
#include "physics/skeleton.hpp"
#include "physics/skinning.hpp"

namespace mane::scenes {

/// A glTF skin: the nodes that act as its joints and, per joint, the inverse bind matrix that
/// takes the mesh from its bind space into the joint's space.
struct CharacterSkin {
  std::string name;
  std::vector<int> joints;                     ///< node indices in `Character::skeleton`
  std::vector<glm::mat4> inverseBindMatrices;  ///< one per joint; identity when the file has none
};

/// One mesh as one node instantiates it, its primitives merged into one surface.
struct CharacterMesh {
  std::string name;  ///< the glTF mesh's name (may be empty)
  int mesh = -1;     ///< index of the mesh in the file
  int node = -1;     ///< the node that holds it; its morph weights live at this node in a pose
  int skin = -1;     ///< index into `Character::skins`, or -1: the mesh rides `node` rigidly
  /// One name per morph target, from the mesh's `extras.targetNames` (empty strings without it).
  std::vector<std::string> morphTargetNames;
  /// Where each glTF primitive starts in `surface`'s vertices, in primitive order.
  std::vector<std::size_t> primitiveFirstVertex;
  /// Where each primitive's triangles start in `surface`'s indices, in primitive order.
  std::vector<std::size_t> primitiveFirstIndex;
  /// Each primitive's glTF material name; empty where it has none (or the material is unnamed).
  std::vector<std::string> primitiveMaterials;
  /// Positions, normals (smooth ones where a primitive has none), tangents (when every primitive
  /// has them), triangles, joint influences with weights renormalised to sum to 1, and morph
  /// targets. Coordinates are the skin's bind space or, without a skin, the node's local space;
  /// metres as glTF specifies. Deforms by linear blend skinning until `setMethod` says otherwise.
  physics::SkinnedMesh surface;
};

struct Character {
  std::string file;  ///< the path it was loaded from, for messages
  /// Every node of the file, with the file's node indices.
  physics::Skeleton skeleton;
  std::vector<CharacterSkin> skins;
  /// Every mesh instance reachable from the default scene, in parent-first node order.
  std::vector<CharacterMesh> meshes;
  /// Every animation, in file order, named as in the file.
  std::vector<physics::AnimationClip> clips;

  /// The first clip named `name`; the error names the file and lists the clips there are.
  [[nodiscard]] Result<const physics::AnimationClip*> findClip(std::string_view name) const;

  /// Index into `meshes` of the first mesh named `name`; the error lists the meshes there are.
  [[nodiscard]] Result<std::size_t> findMesh(std::string_view name) const;

  /// Index of morph target `name` of `meshes[meshIndex]`, which is also its weight's index in the
  /// pose's `morphWeights[mesh.node]`; the error names the mesh and lists its targets.
  [[nodiscard]] Result<std::size_t> findMorphTarget(std::size_t meshIndex, std::string_view name) const;

  /// The joint matrices that deform `meshes[meshIndex]` into world space, given the skeleton's
  /// world matrices (`physics::Skeleton::worldMatrices`): world(joint)·inverseBind(joint) per
  /// joint of its skin, or the world matrix of its node when it has no skin. Fails when the index
  /// or the number of world matrices is wrong.
  [[nodiscard]] Result<std::vector<glm::mat4>> jointMatrices(std::size_t meshIndex,
                                                             std::span<const glm::mat4> world) const;
};

/// Reads `file`. Fails, naming the file and the element (node, skin, mesh and primitive and
/// vertex, animation and channel), when the file is not valid glTF or: nodes do not form trees;
/// a skin's joint is not a node; its inverse-bind accessor is missing from the file, is not a
/// float MAT4, has fewer matrices than joints or holds a NaN or infinity; a skinned primitive
/// lacks JOINTS_0/WEIGHTS_0, has a joint index past the skin's joints, a negative weight, or a
/// vertex whose weights sum to 0; morph targets differ in number between primitives or do not
/// match the mesh's default weights or target names; an animation sampler's key times are not
/// finite and strictly increasing, its output count does not match its keys, or a keyframe is
/// NaN or infinite; a channel animates a node given by a matrix or morph weights of a node
/// without morph targets. Nothing is returned half loaded.
[[nodiscard]] Result<Character> loadCharacter(const std::filesystem::path& file);

}  // namespace mane::scenes
