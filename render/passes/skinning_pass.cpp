#include "render/passes/skinning_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "common/dual_quaternion_joint.hpp"
#include "render/descriptors.hpp"

namespace mane::render {

namespace {

constexpr std::uint32_t kWorkgroupSize = 64;  // local_size_x of skinning.comp

constexpr std::uint32_t kFirstTargetBinding = 8;  // Target0 of skinning.comp

// The std430 elements of skinning.comp.
struct RestVertex {
  glm::vec4 position;
  glm::vec4 normal;
  glm::vec4 tangent;
};
struct Influence {
  glm::uvec4 joints;
  glm::vec4 weights;
};
using MorphDelta = RestVertex;
struct Joint {
  glm::mat4 matrix;
  glm::vec4 real{0.0f};
  glm::vec4 dual{0.0f};
  glm::vec4 stretch[3]{};
};
struct FrameHeader {
  glm::uvec4 counts;  // vertex count, morph target count
};

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool isFinite(const glm::vec4& v) {
  return isFinite(glm::vec3(v)) && std::isfinite(v.w);
}

Result<void> checkMesh(const GpuSkinnedMesh& mesh) {
  const std::size_t vertices = mesh.positions.size();
  const std::size_t influences = mesh.influencesPerVertex;
  if (vertices == 0) return fail("Skinning: the mesh has no vertices.");
  if (influences == 0 || influences > SkinningPass::kMaxInfluences)
    return fail("Skinning: " + std::to_string(influences) + " influences per vertex; the pass takes 1 to 8.");
  if (mesh.joints.size() != vertices * influences || mesh.weights.size() != vertices * influences)
    return fail("Skinning: " + std::to_string(vertices) + " vertices need " + std::to_string(vertices * influences) +
                " joints and weights; got " + std::to_string(mesh.joints.size()) + " and " +
                std::to_string(mesh.weights.size()) + ".");
  if ((!mesh.normals.empty() && mesh.normals.size() != vertices) ||
      (!mesh.tangents.empty() && mesh.tangents.size() != vertices))
    return fail("Skinning: the normals or tangents do not match the " + std::to_string(vertices) + " vertices.");
  for (std::size_t v = 0; v < vertices; ++v) {
    const std::string vertex = "Skinning: vertex " + std::to_string(v);
    if (!isFinite(mesh.positions[v]) || (!mesh.normals.empty() && !isFinite(mesh.normals[v])) ||
        (!mesh.tangents.empty() && !isFinite(mesh.tangents[v])))
      return fail(vertex + " has a NaN or infinite position, normal or tangent.");
    float sum = 0.0f;
    for (std::size_t i = v * influences; i < (v + 1) * influences; ++i) {
      if (mesh.joints[i] >= mesh.jointCount)
        return fail(vertex + " is bound to joint " + std::to_string(mesh.joints[i]) + " of " +
                    std::to_string(mesh.jointCount) + ".");
      if (!std::isfinite(mesh.weights[i]) || mesh.weights[i] < 0.0f)
        return fail(vertex + " has a negative, NaN or infinite weight.");
      sum += mesh.weights[i];
    }
    if (!(sum > 0.0f) || !std::isfinite(sum)) return fail(vertex + "'s weights do not sum to a positive number.");
  }
  for (std::size_t k = 0; k < mesh.morphTargets.size(); ++k) {
    const GpuMorphTarget& target = mesh.morphTargets[k];
    for (const auto* deltas : {&target.positionDeltas, &target.normalDeltas, &target.tangentDeltas}) {
      if (!deltas->empty() && deltas->size() != vertices)
        return fail("Skinning: morph target " + std::to_string(k) + " has " + std::to_string(deltas->size()) +
                    " deltas for " + std::to_string(vertices) + " vertices.");
      if (!std::ranges::all_of(*deltas, [](const glm::vec3& d) { return isFinite(d); }))
        return fail("Skinning: morph target " + std::to_string(k) + " has a NaN or infinite delta.");
    }
  }
  return {};
}

Result<void> checkLimits(const GpuSkinnedMesh& mesh, const vk::PhysicalDeviceLimits& limits) {
  const std::uint64_t vertices = mesh.positions.size();
  if ((vertices + kWorkgroupSize - 1) / kWorkgroupSize > limits.maxComputeWorkGroupCount[0])
    return fail("Skinning: " + std::to_string(vertices) + " vertices need more workgroups than the device allows.");
  const std::uint64_t morphBytes = vertices * mesh.morphTargets.size() * sizeof(MorphDelta);
  const std::uint64_t jointBytes = std::uint64_t(mesh.jointCount) * sizeof(Joint);
  if (std::max({vertices * sizeof(RestVertex), morphBytes, jointBytes}) > limits.maxStorageBufferRange)
    return fail("Skinning: the mesh's buffers exceed the device's storage buffer range of " +
                std::to_string(limits.maxStorageBufferRange) + " bytes.");
  return {};
}

Result<void> checkTargets(std::span<const SkinnedVertexTarget> targets, std::size_t vertices) {
  if (targets.size() > SkinningPass::kMaxVertexTargets)
    return fail("Skinning: " + std::to_string(targets.size()) + " vertex targets; the pass writes at most " +
                std::to_string(SkinningPass::kMaxVertexTargets) + ".");
  for (std::size_t t = 0; t < targets.size(); ++t) {
    const SkinnedVertexTarget& target = targets[t];
    const std::string name = "Skinning: vertex target " + std::to_string(t);
    if (target.buffer == nullptr || !(target.buffer->usage() & vk::BufferUsageFlagBits::eStorageBuffer))
      return fail(name + " has no buffer, or one without STORAGE_BUFFER usage.");
    if (std::max(target.positionOffset, target.normalOffset) + 3 > target.stride)
      return fail(name + "'s position or normal does not fit in its stride of " + std::to_string(target.stride) +
                  " floats.");
    const std::uint64_t bytes = std::uint64_t(vertices) * target.stride * sizeof(float);
    if (target.buffer->size() < bytes)
      return fail(name + " holds " + std::to_string(target.buffer->size()) + " bytes; " +
                  std::to_string(vertices) + " vertices need " + std::to_string(bytes) + ".");
  }
  return {};
}

// Influences rounded up to whole groups of 4 (the shader's uvec4/vec4), weights renormalised to
// sum to 1; padding influences have weight 0, which adds nothing.
std::vector<Influence> packInfluences(const GpuSkinnedMesh& mesh, std::uint32_t groups) {
  const std::size_t influences = mesh.influencesPerVertex;
  std::vector<Influence> packed(mesh.positions.size() * groups, Influence{glm::uvec4(0), glm::vec4(0.0f)});
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    float sum = 0.0f;
    for (std::size_t i = 0; i < influences; ++i) sum += mesh.weights[v * influences + i];
    for (std::size_t i = 0; i < influences; ++i) {
      Influence& group = packed[v * groups + i / 4];
      group.joints[int(i % 4)] = mesh.joints[v * influences + i];
      group.weights[int(i % 4)] = mesh.weights[v * influences + i] / sum;
    }
  }
  return packed;
}

std::vector<RestVertex> packRest(const GpuSkinnedMesh& mesh) {
  std::vector<RestVertex> rest(mesh.positions.size());
  for (std::size_t v = 0; v < rest.size(); ++v) {
    rest[v].position = glm::vec4(mesh.positions[v], 1.0f);
    rest[v].normal = mesh.normals.empty() ? glm::vec4(0.0f) : glm::vec4(mesh.normals[v], 0.0f);
    rest[v].tangent = mesh.tangents.empty() ? glm::vec4(0.0f) : mesh.tangents[v];
  }
  return rest;
}

// Target-major deltas; an attribute the mesh lacks gets none, as the CPU path leaves it alone.
std::vector<MorphDelta> packMorphs(const GpuSkinnedMesh& mesh) {
  const std::size_t vertices = mesh.positions.size();
  // At least one element: Vulkan has no empty buffers.
  std::vector<MorphDelta> deltas(std::max<std::size_t>(1, vertices * mesh.morphTargets.size()),
                                 MorphDelta{glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f)});
  for (std::size_t k = 0; k < mesh.morphTargets.size(); ++k) {
    const GpuMorphTarget& target = mesh.morphTargets[k];
    for (std::size_t v = 0; v < vertices; ++v) {
      MorphDelta& d = deltas[k * vertices + v];
      if (!target.positionDeltas.empty()) d.position = glm::vec4(target.positionDeltas[v], 0.0f);
      if (!mesh.normals.empty() && !target.normalDeltas.empty()) d.normal = glm::vec4(target.normalDeltas[v], 0.0f);
      if (!mesh.tangents.empty() && !target.tangentDeltas.empty()) d.tangent = glm::vec4(target.tangentDeltas[v], 0.0f);
    }
  }
  return deltas;
}

// The DQS parts of the joint's matrix (common/dual_quaternion_joint.hpp) in the shader's layout.
void decompose(Joint& joint) {
  const DualQuaternionJoint parts = decomposeJoint(joint.matrix);
  joint.real = parts.real;
  joint.dual = parts.dual;
  for (int c = 0; c < 3; ++c) joint.stretch[c] = glm::vec4(parts.stretch[c], 0.0f);
}

}  // namespace

Result<std::unique_ptr<SkinningPass>> SkinningPass::create(const Device& device, const GpuSkinnedMesh& mesh,
                                                           const SkinningSettings& settings) {
  // The shader indexes joints with the mesh's numbers: one out of range would read outside its buffer.
  if (auto valid = checkMesh(mesh); !valid) return std::unexpected(valid.error());
  if (auto fits = checkLimits(mesh, device.limits()); !fits) return std::unexpected(fits.error());
  if (auto targets = checkTargets(settings.vertexTargets, mesh.positions.size()); !targets)
    return std::unexpected(targets.error());
  try {
    return std::unique_ptr<SkinningPass>(new SkinningPass(device, mesh, settings));
  } catch (const std::exception& error) {
    return fail(std::string("Skinning: creating the pass failed: ") + error.what());
  }
}

SkinningPass::SkinningPass(const Device& device, const GpuSkinnedMesh& mesh, const SkinningSettings& settings)
    : vertexCount_(static_cast<std::uint32_t>(mesh.positions.size())),
      jointCount_(mesh.jointCount),
      targetCount_(static_cast<std::uint32_t>(mesh.morphTargets.size())),
      method_(mesh.method),
      hostReadable_(settings.hostReadable),
      vertexTargets_(settings.vertexTargets) {
  const std::uint32_t groups = (mesh.influencesPerVertex + 3) / 4;
  const auto storage = vk::BufferUsageFlagBits::eStorageBuffer;
  const auto hostMemory = vk::MemoryPropertyFlagBits::eHostVisible | vk::MemoryPropertyFlagBits::eHostCoherent;
  const auto upload = [&](const auto& elements) {
    return Buffer::withData(device, std::as_bytes(std::span(elements)), storage);
  };
  rest_ = upload(packRest(mesh));
  influences_ = upload(packInfluences(mesh, groups));
  morphs_ = upload(packMorphs(mesh));
  frame_ =
      Buffer(device, sizeof(FrameHeader) + sizeof(float) * std::max<std::size_t>(1, targetCount_), storage, hostMemory);
  std::memset(frame_.mapped().data(), 0, frame_.mapped().size());
  const FrameHeader header{glm::uvec4(vertexCount_, targetCount_, 0, 0)};
  std::memcpy(frame_.mapped().data(), &header, sizeof(header));
  // Identity joints until the first update: the rest pose rather than a collapsed mesh.
  std::vector<Joint> identity(std::max<std::uint32_t>(1, jointCount_), Joint{glm::mat4(1.0f)});
  for (Joint& joint : identity) decompose(joint);
  joints_ = Buffer(device, identity.size() * sizeof(Joint), storage, hostMemory);
  std::memcpy(joints_.mapped().data(), identity.data(), identity.size() * sizeof(Joint));

  const vk::DeviceSize outputBytes = vk::DeviceSize(vertexCount_) * kVertexStride;
  const auto outputUsage = storage | vk::BufferUsageFlagBits::eVertexBuffer | vk::BufferUsageFlagBits::eTransferSrc;
  const vk::MemoryPropertyFlags outputMemory = hostReadable_ ? hostMemory : vk::MemoryPropertyFlagBits::eDeviceLocal;
  positions_ = Buffer(device, outputBytes, outputUsage, outputMemory);
  normals_ = Buffer(device, outputBytes, outputUsage, outputMemory);
  tangents_ = Buffer(device, outputBytes, outputUsage, outputMemory);

  const auto compute = vk::ShaderStageFlagBits::eCompute;
  const std::pair<vk::DescriptorType, vk::ShaderStageFlags> binding{vk::DescriptorType::eStorageBuffer, compute};
  constexpr std::uint32_t kBindings = kFirstTargetBinding + kMaxVertexTargets;
  static_assert(kBindings == 11);
  setLayout_ = makeSetLayout(
      device, {binding, binding, binding, binding, binding, binding, binding, binding, binding, binding, binding});
  const bool dualQuaternion = method_ == GpuSkinningMethod::DualQuaternion;
  SpecializationConstants constants{groups, dualQuaternion ? 1u : 0u, std::uint32_t(vertexTargets_.size())};
  for (std::uint32_t t = 0; t < kMaxVertexTargets; ++t) {
    const SkinnedVertexTarget target = t < vertexTargets_.size() ? vertexTargets_[t] : SkinnedVertexTarget{.stride = 3};
    constants.insert(constants.end(), {target.stride, target.positionOffset, target.normalOffset});
  }
  pipeline_ = makeComputePipeline(device, "skinning.comp", setLayout_, 0, constants);

  pool_ = makeDescriptorPool(device, 1, {{vk::DescriptorType::eStorageBuffer, kBindings}});
  set_ = allocateSet(device, pool_, setLayout_);
  const Buffer* buffers[] = {&rest_, &influences_, &morphs_, &frame_, &joints_, &positions_, &normals_, &tangents_};
  for (std::uint32_t b = 0; b < kFirstTargetBinding; ++b) writeStorageBuffer(device, set_, b, *buffers[b]);
  // Targets the mesh does not have are bound to an output, valid and never written (kVertexTargets).
  for (std::uint32_t t = 0; t < kMaxVertexTargets; ++t)
    writeStorageBuffer(device, set_, kFirstTargetBinding + t,
                       t < vertexTargets_.size() ? *vertexTargets_[t].buffer : positions_);
}

Result<void> SkinningPass::update(std::span<const glm::mat4> jointMatrices, std::span<const float> morphWeights) {
  if (jointMatrices.size() != jointCount_ || morphWeights.size() != targetCount_)
    return fail("Skinning: the mesh needs " + std::to_string(jointCount_) + " joint matrices and " +
                std::to_string(targetCount_) + " morph weights; got " + std::to_string(jointMatrices.size()) + " and " +
                std::to_string(morphWeights.size()) + ".");
  if (!std::ranges::all_of(morphWeights, [](float w) { return std::isfinite(w); }))
    return fail("Skinning: a morph weight is NaN or infinite.");
  std::vector<Joint> joints(jointMatrices.size());
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const glm::mat4& m = jointMatrices[j];
    if (!isFinite(m[0]) || !isFinite(m[1]) || !isFinite(m[2]) || !isFinite(m[3]))
      return fail("Skinning: joint matrix " + std::to_string(j) + " has a NaN or infinite entry.");
    joints[j].matrix = m;
    if (method_ != GpuSkinningMethod::DualQuaternion) continue;
    if (!(glm::determinant(glm::dmat3(glm::mat3(m))) > 0.0))
      return fail("Skinning: joint matrix " + std::to_string(j) +
                  " mirrors or flattens space (determinant <= 0); dual-quaternion skinning needs a rotation.");
    decompose(joints[j]);
  }
  // Copied as byte ranges, not with memcpy: a mesh without morph targets (or joints) hands over
  // an empty span whose data() is null, which memcpy may not be given even for zero bytes.
  std::ranges::copy(std::as_bytes(std::span(joints)), joints_.mapped().begin());
  std::ranges::copy(std::as_bytes(morphWeights), frame_.mapped().begin() + sizeof(FrameHeader));
  return {};
}

void SkinningPass::declare(FrameGraph::Builder& pass) const {
  // The frame's inputs need nothing: host writes before vkQueueSubmit are visible to it.
  for (const Buffer* output : {&positions_, &normals_, &tangents_})
    pass.write(*output, ResourceUse::storageWrite(vk::PipelineStageFlagBits2::eComputeShader));
  // Other passes' vertex buffers: they draw them without declaring a read (they are static to
  // them), so the pass makes its writes visible itself (execute).
  for (const SkinnedVertexTarget& target : vertexTargets_)
    pass.produce(*target.buffer, ResourceUse::computedVertices(false));
}

void SkinningPass::execute(const vk::raii::CommandBuffer& commands) const {
  commands.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_.pipeline);
  commands.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *pipeline_.layout, 0, {*set_}, {});
  commands.dispatch((vertexCount_ + kWorkgroupSize - 1) / kWorkgroupSize, 1, 1);
  if (vertexTargets_.empty()) return;
  // Earlier readers of the targets (a previous frame's draws) need nothing here: the caller
  // waits for each frame before the next one updates the joints (update).
  const ResourceUse readers = ResourceUse::computedVertices(false);
  std::vector<vk::BufferMemoryBarrier2> barriers;
  for (const SkinnedVertexTarget& target : vertexTargets_)
    barriers.push_back({.srcStageMask = vk::PipelineStageFlagBits2::eComputeShader,
                        .srcAccessMask = vk::AccessFlagBits2::eShaderStorageWrite,
                        .dstStageMask = readers.stages,
                        .dstAccessMask = readers.access,
                        .buffer = *target.buffer->buffer(),
                        .offset = 0,
                        .size = VK_WHOLE_SIZE});
  commands.pipelineBarrier2({.bufferMemoryBarrierCount = static_cast<std::uint32_t>(barriers.size()),
                             .pBufferMemoryBarriers = barriers.data()});
}

void SkinningPass::record(const vk::raii::CommandBuffer& commands) const {
  const ResourceUse readers = ResourceUse::computedVertices(hostReadable_);
  FrameGraph::recordAlone(commands, PassName::kSkinning, *this,
                          {{positions_, readers}, {normals_, readers}, {tangents_, readers}});
}

std::span<const glm::vec4> SkinningPass::mapped(const Buffer& buffer) const {
  if (!hostReadable_) return {};
  return {reinterpret_cast<const glm::vec4*>(buffer.mapped().data()), vertexCount_};
}
std::span<const glm::vec4> SkinningPass::mappedPositions() const {
  return mapped(positions_);
}
std::span<const glm::vec4> SkinningPass::mappedNormals() const {
  return mapped(normals_);
}
std::span<const glm::vec4> SkinningPass::mappedTangents() const {
  return mapped(tangents_);
}

}  // namespace mane::render
