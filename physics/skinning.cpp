#include "physics/skinning.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "common/dual_quaternion_joint.hpp"
#include "physics/detail/parallel_tasks.hpp"

namespace mane::physics {
namespace {

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool isFinite(const glm::vec4& v) {
  return isFinite(glm::vec3(v)) && std::isfinite(v.w);
}

bool isFinite(const glm::mat4& m) {
  return isFinite(m[0]) && isFinite(m[1]) && isFinite(m[2]) && isFinite(m[3]);
}

/// Columns c1×c2, c2×c0, c0×c1: det(L)·L⁻ᵀ, the matrix that carries normals.
glm::mat3 cofactor(const glm::mat3& l) {
  return glm::mat3(glm::cross(l[1], l[2]), glm::cross(l[2], l[0]), glm::cross(l[0], l[1]));
}

/// `v` scaled to unit length, or `fallback` when it has no length.
glm::vec3 normalisedOr(const glm::vec3& v, const glm::vec3& fallback) {
  const float length = glm::length(v);
  return length > 0.0f && std::isfinite(length) ? v / length : fallback;
}

/// Rotates `v` by the unit quaternion `q` (x, y, z, w): v + 2·r × (r × v + w·v).
glm::vec3 rotate(const glm::vec4& q, const glm::vec3& v) {
  const glm::vec3 r(q);
  return v + 2.0f * glm::cross(r, glm::cross(r, v) + q.w * v);
}

/// A vertex bound (with a non-zero weight) to a joint whose matrix DQS cannot take.
struct ImproperBinding {
  std::size_t vertex;
  std::uint32_t joint;
};

/// SkinnedMesh::deform's work for vertices [begin, end) of `d`, into `out` (sized). Stops at the
/// first improper binding (DQS) and names it.
std::optional<ImproperBinding> deformRange(const SkinnedMeshData& d, std::span<const glm::mat4> jointMatrices,
                                           std::span<const DualQuaternionJoint> dualQuaternions,
                                           std::span<const float> morphWeights, DeformedSurface& out,
                                           std::size_t begin, std::size_t end) {
  const bool dualQuaternion = d.method == SkinningMethod::DualQuaternion;
  const std::size_t influences = d.influencesPerVertex;
  const bool hasNormals = !d.normals.empty();
  const bool hasTangents = !d.tangents.empty();
  for (std::size_t v = begin; v < end; ++v) {
    // 1. Morph targets, in target order.
    glm::vec3 position = d.positions[v];
    glm::vec3 normal = hasNormals ? d.normals[v] : glm::vec3(0.0f);
    glm::vec4 tangent = hasTangents ? d.tangents[v] : glm::vec4(0.0f);
    for (std::size_t k = 0; k < d.morphTargets.size(); ++k) {
      const float w = morphWeights[k];
      if (w == 0.0f) continue;
      const MorphTarget& target = d.morphTargets[k];
      if (!target.positionDeltas.empty()) position += w * target.positionDeltas[v];
      if (hasNormals && !target.normalDeltas.empty()) normal += w * target.normalDeltas[v];
      if (hasTangents && !target.tangentDeltas.empty()) tangent += glm::vec4(w * target.tangentDeltas[v], 0.0f);
    }
    const glm::vec3 restNormal = hasNormals ? normalisedOr(normal, d.normals[v]) : glm::vec3(0.0f);
    const glm::vec3 restTangent =
        hasTangents ? normalisedOr(glm::vec3(tangent), glm::vec3(d.tangents[v])) : glm::vec3(0.0f);

    // 2. Skinning.
    const std::size_t first = v * influences;
    if (!dualQuaternion) {
      glm::mat4 blended(0.0f);
      for (std::size_t i = first; i < first + influences; ++i) {
        blended += d.weights[i] * jointMatrices[d.joints[i]];
      }
      out.positions[v] = glm::vec3(blended * glm::vec4(position, 1.0f));
      const glm::mat3 linear(blended);
      if (hasNormals) {
        const float handedness = glm::determinant(linear) < 0.0f ? -1.0f : 1.0f;
        out.normals[v] = normalisedOr(handedness * (cofactor(linear) * restNormal), restNormal);
      }
      if (hasTangents) {
        const float mirror = glm::determinant(linear) < 0.0f ? -1.0f : 1.0f;
        out.tangents[v] = glm::vec4(normalisedOr(linear * restTangent, restTangent), tangent.w * mirror);
      }
      continue;
    }

    // DQS: antipodal quaternions are the same rotation; align every influence with the first
    // weighted one so that blending takes the short way round.
    std::size_t pivotInfluence = first;
    while (pivotInfluence + 1 < first + influences && d.weights[pivotInfluence] == 0.0f) ++pivotInfluence;
    const glm::vec4 pivot = dualQuaternions[d.joints[pivotInfluence]].real;
    glm::vec4 real(0.0f);
    glm::vec4 dual(0.0f);
    glm::mat3 stretch(0.0f);
    for (std::size_t i = first; i < first + influences; ++i) {
      const float w = d.weights[i];
      if (w == 0.0f) continue;
      const DualQuaternionJoint& joint = dualQuaternions[d.joints[i]];
      if (!joint.proper) return ImproperBinding{v, d.joints[i]};
      const float signedWeight = glm::dot(joint.real, pivot) < 0.0f ? -w : w;
      real += signedWeight * joint.real;
      dual += signedWeight * joint.dual;
      stretch += w * joint.stretch;
    }
    const float length = glm::length(real);
    real /= length;
    dual /= length;
    // Translation of the blended motion: 2·dual·conj(real), vector part.
    const glm::vec3 rv(real);
    const glm::vec3 dv(dual);
    const glm::vec3 translation = 2.0f * (real.w * dv - dual.w * rv + glm::cross(rv, dv));
    out.positions[v] = rotate(real, stretch * position) + translation;
    if (hasNormals) out.normals[v] = normalisedOr(rotate(real, cofactor(stretch) * restNormal), restNormal);
    if (hasTangents) {
      out.tangents[v] = glm::vec4(normalisedOr(rotate(real, stretch * restTangent), restTangent), tangent.w);
    }
  }
  return std::nullopt;
}

}  // namespace

Result<SkinnedMesh> SkinnedMesh::create(SkinnedMeshData data) {
  const std::size_t vertices = data.positions.size();
  const std::size_t influences = data.influencesPerVertex;
  if (influences == 0) return fail("a skinned mesh needs at least one joint influence per vertex");
  if (data.joints.size() != vertices * influences || data.weights.size() != vertices * influences) {
    return fail("a skinned mesh of " + std::to_string(vertices) + " vertices with " + std::to_string(influences) +
                " influences each needs " + std::to_string(vertices * influences) + " joints and weights; got " +
                std::to_string(data.joints.size()) + " joints and " + std::to_string(data.weights.size()) + " weights");
  }
  if (!data.normals.empty() && data.normals.size() != vertices) {
    return fail("a skinned mesh has " + std::to_string(data.normals.size()) + " normals for " +
                std::to_string(vertices) + " vertices");
  }
  if (!data.tangents.empty() && data.tangents.size() != vertices) {
    return fail("a skinned mesh has " + std::to_string(data.tangents.size()) + " tangents for " +
                std::to_string(vertices) + " vertices");
  }
  for (std::size_t v = 0; v < vertices; ++v) {
    const std::string vertex = "vertex " + std::to_string(v);
    if (!isFinite(data.positions[v])) return fail(vertex + " has a NaN or infinite position");
    if (!data.normals.empty() && !isFinite(data.normals[v])) return fail(vertex + " has a NaN or infinite normal");
    if (!data.tangents.empty() && !isFinite(data.tangents[v])) return fail(vertex + " has a NaN or infinite tangent");
    float sum = 0.0f;
    for (std::size_t i = v * influences; i < (v + 1) * influences; ++i) {
      if (data.joints[i] >= data.jointCount) {
        return fail(vertex + " is bound to joint " + std::to_string(data.joints[i]) + ", but the skin has " +
                    std::to_string(data.jointCount) + " joints");
      }
      const float w = data.weights[i];
      if (!std::isfinite(w) || w < 0.0f) {
        return fail(vertex + " has joint weight " + std::to_string(w) + "; weights must be finite and >= 0");
      }
      sum += w;
    }
    if (!(sum > 0.0f) || !std::isfinite(sum)) {
      return fail(vertex + "'s joint weights sum to " + std::to_string(sum) + "; they must sum to a positive number");
    }
    for (std::size_t i = v * influences; i < (v + 1) * influences; ++i) data.weights[i] /= sum;
  }
  for (std::size_t i = 0; i < data.indices.size(); ++i) {
    if (data.indices[i] >= vertices) {
      return fail("triangle index " + std::to_string(i) + " is " + std::to_string(data.indices[i]) +
                  ", but the mesh has " + std::to_string(vertices) + " vertices");
    }
  }
  if (data.indices.size() % 3 != 0) {
    return fail("a skinned mesh has " + std::to_string(data.indices.size()) + " indices, not a multiple of 3");
  }
  for (std::size_t k = 0; k < data.morphTargets.size(); ++k) {
    const MorphTarget& target = data.morphTargets[k];
    const std::string what =
        "morph target " + std::to_string(k) + (target.name.empty() ? "" : " ('" + target.name + "')");
    const auto check = [&](const std::vector<glm::vec3>& deltas, const char* attribute) -> Result<void> {
      if (!deltas.empty() && deltas.size() != vertices) {
        return fail(what + " has " + std::to_string(deltas.size()) + " " + attribute + " deltas for " +
                    std::to_string(vertices) + " vertices");
      }
      for (std::size_t v = 0; v < deltas.size(); ++v) {
        if (!isFinite(deltas[v]))
          return fail(what + " has a NaN or infinite " + attribute + " delta at vertex " + std::to_string(v));
      }
      return {};
    };
    if (auto ok = check(target.positionDeltas, "position"); !ok) return std::unexpected(ok.error());
    if (auto ok = check(target.normalDeltas, "normal"); !ok) return std::unexpected(ok.error());
    if (auto ok = check(target.tangentDeltas, "tangent"); !ok) return std::unexpected(ok.error());
  }
  SkinnedMesh mesh;
  mesh.data_ = std::move(data);
  return mesh;
}

Result<void> SkinnedMesh::deform(std::span<const glm::mat4> jointMatrices, std::span<const float> morphWeights,
                                 DeformedSurface& out, unsigned threads) const {
  return deform(jointMatrices, morphWeights, out, builtInTaskRunner(threads));
}

Result<void> SkinnedMesh::deform(std::span<const glm::mat4> jointMatrices, std::span<const float> morphWeights,
                                 DeformedSurface& out, const TaskRunner& tasks) const {
  const SkinnedMeshData& d = data_;
  if (jointMatrices.size() != d.jointCount) {
    return fail("deforming a skinned mesh needs " + std::to_string(d.jointCount) + " joint matrices; got " +
                std::to_string(jointMatrices.size()));
  }
  if (morphWeights.size() != d.morphTargets.size()) {
    return fail("deforming a skinned mesh needs " + std::to_string(d.morphTargets.size()) + " morph weights; got " +
                std::to_string(morphWeights.size()));
  }
  for (std::size_t j = 0; j < jointMatrices.size(); ++j) {
    if (!isFinite(jointMatrices[j])) return fail("joint matrix " + std::to_string(j) + " has a NaN or infinite entry");
  }
  for (std::size_t k = 0; k < morphWeights.size(); ++k) {
    if (!std::isfinite(morphWeights[k])) return fail("morph weight " + std::to_string(k) + " is NaN or infinite");
  }

  const bool dualQuaternion = d.method == SkinningMethod::DualQuaternion;
  std::vector<DualQuaternionJoint> dualQuaternions;
  if (dualQuaternion) {
    dualQuaternions.reserve(jointMatrices.size());
    for (const glm::mat4& m : jointMatrices) dualQuaternions.push_back(decomposeJoint(m));
  }

  const std::size_t vertices = d.positions.size();
  out.positions.resize(vertices);
  out.normals.resize(d.normals.empty() ? 0 : vertices);
  out.tangents.resize(d.tangents.empty() ? 0 : vertices);
  if (vertices == 0) return {};

  // A fixed partition into contiguous vertex ranges, one per task; each vertex's arithmetic does
  // not depend on it, so the output has the same bits whatever runs the tasks.
  const std::uint32_t workers = detail::taskCountFor(tasks, vertices);
  const auto rangeBegin = [&](std::uint32_t w) { return detail::taskRangeBegin(vertices, workers, w); };
  std::vector<std::optional<ImproperBinding>> failures(workers);
  auto run = [&](std::uint32_t w) {
    failures[w] = deformRange(d, jointMatrices, dualQuaternions, morphWeights, out, rangeBegin(w), rangeBegin(w + 1));
  };
  if (auto ran = detail::runTasks(tasks, workers, run); !ran) return fail("skinning: " + ran.error().message);
  // The first failing vertex in vertex order, whatever the partition.
  for (const std::optional<ImproperBinding>& failure : failures) {
    if (!failure) continue;
    return fail("vertex " + std::to_string(failure->vertex) + " is bound to joint " + std::to_string(failure->joint) +
                ", whose matrix mirrors or flattens space (determinant <= 0); dual-quaternion skinning "
                "needs a rotation");
  }
  return {};
}

}  // namespace mane::physics
