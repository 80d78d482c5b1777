#include "physics/skeleton.hpp"

#include <cmath>
#include <utility>

namespace mane::physics {
namespace {

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool isFinite(const glm::quat& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}

bool isFinite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

std::string nodeLabel(const std::vector<SkeletonNode>& nodes, std::size_t index) {
  std::string label = "node " + std::to_string(index);
  if (!nodes[index].name.empty()) label += " ('" + nodes[index].name + "')";
  return label;
}

}  // namespace

glm::mat4 localMatrix(const NodeTransform& transform) {
  glm::mat4 m = glm::mat4_cast(transform.rotation);
  m[0] *= transform.scale.x;
  m[1] *= transform.scale.y;
  m[2] *= transform.scale.z;
  m[3] = glm::vec4(transform.translation, 1.0f);
  return m;
}

Result<Skeleton> Skeleton::create(std::vector<SkeletonNode> nodes) {
  const std::size_t count = nodes.size();
  std::vector<std::vector<int>> children(count);
  std::vector<int> roots;
  for (std::size_t i = 0; i < count; ++i) {
    const SkeletonNode& node = nodes[i];
    if (node.parent < -1 || node.parent >= static_cast<int>(count)) {
      return fail(nodeLabel(nodes, i) + " has parent " + std::to_string(node.parent) +
                  "; expected -1 or a node below " + std::to_string(count));
    }
    if (!isFinite(node.rest.translation) || !isFinite(node.rest.rotation) || !isFinite(node.rest.scale)) {
      return fail(nodeLabel(nodes, i) + " has a rest transform with a NaN or infinite component");
    }
    if (glm::dot(node.rest.rotation, node.rest.rotation) == 0.0f) {
      return fail(nodeLabel(nodes, i) + " has a zero rest rotation quaternion; expected a unit quaternion");
    }
    if (node.fixedMatrix && !isFinite(*node.fixedMatrix)) {
      return fail(nodeLabel(nodes, i) + " has a matrix with a NaN or infinite entry");
    }
    for (float w : node.restMorphWeights) {
      if (!std::isfinite(w)) return fail(nodeLabel(nodes, i) + " has a NaN or infinite rest morph weight");
    }
    if (node.parent < 0) {
      roots.push_back(static_cast<int>(i));
    } else {
      children[static_cast<std::size_t>(node.parent)].push_back(static_cast<int>(i));
    }
  }

  // Depth-first from each root with an explicit stack: a hostile file may nest thousands deep.
  // Children are pushed in reverse so that they come out in index order.
  std::vector<int> order;
  order.reserve(count);
  std::vector<int> stack;
  for (int root : roots) {
    stack.push_back(root);
    while (!stack.empty()) {
      const int node = stack.back();
      stack.pop_back();
      order.push_back(node);
      const auto& below = children[static_cast<std::size_t>(node)];
      for (auto it = below.rbegin(); it != below.rend(); ++it) stack.push_back(*it);
    }
  }
  if (order.size() != count) {
    // Every node has one parent, so a node that no root reaches lies on a cycle of parents.
    std::vector<bool> reached(count, false);
    for (int node : order) reached[static_cast<std::size_t>(node)] = true;
    std::size_t first = 0;
    while (reached[first]) ++first;
    return fail(nodeLabel(nodes, first) + " is its own ancestor: the parents form a cycle");
  }

  Skeleton skeleton;
  skeleton.nodes_ = std::move(nodes);
  skeleton.order_ = std::move(order);
  return skeleton;
}

Pose Skeleton::restPose() const {
  Pose pose;
  pose.local.reserve(nodes_.size());
  pose.morphWeights.reserve(nodes_.size());
  for (const SkeletonNode& node : nodes_) {
    pose.local.push_back(node.rest);
    pose.morphWeights.push_back(node.restMorphWeights);
  }
  return pose;
}

Result<void> Skeleton::worldMatrices(std::span<const NodeTransform> local, std::span<glm::mat4> world) const {
  if (local.size() != nodes_.size() || world.size() != nodes_.size()) {
    return fail("world matrices need one local transform and one output per node: the skeleton has " +
                std::to_string(nodes_.size()) + " nodes, got " + std::to_string(local.size()) + " transforms and " +
                std::to_string(world.size()) + " outputs");
  }
  for (int index : order_) {
    const auto i = static_cast<std::size_t>(index);
    const SkeletonNode& node = nodes_[i];
    const glm::mat4 own = node.fixedMatrix ? *node.fixedMatrix : localMatrix(local[i]);
    world[i] = node.parent < 0 ? own : world[static_cast<std::size_t>(node.parent)] * own;
  }
  return {};
}

Result<std::vector<glm::mat4>> Skeleton::worldMatrices(const Pose& pose) const {
  std::vector<glm::mat4> world(nodes_.size());
  if (auto ok = worldMatrices(pose.local, world); !ok) return std::unexpected(ok.error());
  return world;
}

}  // namespace mane::physics
