#pragma once
// A character's node hierarchy: each node's parent, its rest transform and its world matrix for
// any pose. The hierarchy is the one a glTF file describes (glTF 2.0 §3.5): a node's local
// transform is T·R·S, and its world matrix is its parent's world matrix times that. Joints of a
// skin are simply nodes of this hierarchy; meshes hang off nodes too.
//
// World matrices are composed in a fixed parent-first order computed once at creation, so any
// pose gives the same bits on every run and thread count.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "common/error.hpp"

namespace mane::physics {

/// A node's local transform as glTF stores and animates it: x_parent = T · R · S · x_local.
struct NodeTransform {
  glm::vec3 translation{0.0f};                 ///< metres
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  ///< unit quaternion (glm order: w, x, y, z)
  glm::vec3 scale{1.0f};                       ///< per local axis, dimensionless
};

/// The matrix T · R · S of `transform`; the rotation is used as given (callers keep it unit).
[[nodiscard]] glm::mat4 localMatrix(const NodeTransform& transform);

/// One node of a hierarchy, as `Skeleton::create` takes it.
struct SkeletonNode {
  std::string name;
  /// Index of the parent node, or −1 for a root.
  int parent = -1;
  /// The local transform when nothing animates the node.
  NodeTransform rest;
  /// Set when the file gave the node a full matrix instead of TRS: it is used in place of the
  /// pose's transform, because a general matrix (shear) has no TRS form. glTF forbids animating
  /// such a node, so the pose's entry for it is ignored.
  std::optional<glm::mat4> fixedMatrix;
  /// Morph target weights of the mesh this node instantiates when nothing animates them (glTF:
  /// node.weights, else mesh.weights, else zeros); empty when the node has no morphing mesh.
  std::vector<float> restMorphWeights;
};

/// A hierarchy's state at one instant: every node's local transform and, per node, the morph
/// weights of its mesh (empty for nodes without morph targets).
struct Pose {
  std::vector<NodeTransform> local;
  std::vector<std::vector<float>> morphWeights;
};

class Skeleton {
public:
  /// An empty hierarchy (no nodes).
  Skeleton() = default;

  /// Checks and takes `nodes`. Fails, naming the node, when a parent index is out of range, the
  /// parents form a cycle, or a rest transform or fixed matrix holds a NaN or infinity or a zero
  /// rotation quaternion.
  [[nodiscard]] static Result<Skeleton> create(std::vector<SkeletonNode> nodes);

  [[nodiscard]] std::span<const SkeletonNode> nodes() const { return nodes_; }
  [[nodiscard]] std::size_t nodeCount() const { return nodes_.size(); }

  /// Every node index, each after its parent (roots, then their subtrees, in index order).
  [[nodiscard]] std::span<const int> parentFirstOrder() const { return order_; }

  /// The pose in which every node has its rest transform and rest morph weights.
  [[nodiscard]] Pose restPose() const;

  /// World matrices (node → world) of `local`, one per node, written to `world`. Fails when
  /// either span's size is not `nodeCount()`.
  [[nodiscard]] Result<void> worldMatrices(std::span<const NodeTransform> local, std::span<glm::mat4> world) const;

  /// `worldMatrices` of a pose, into a new vector.
  [[nodiscard]] Result<std::vector<glm::mat4>> worldMatrices(const Pose& pose) const;

private:
  std::vector<SkeletonNode> nodes_;
  std::vector<int> order_;
};

}  // namespace mane::physics
