// Skinning a character-sized mesh: the CPU path (physics::SkinnedMesh::deform) at 1 and 2
// threads against the GPU pass (render/passes/skinning_pass.hpp), the same mesh and pose in the
// same run, so the ratio can be quoted.
//
//   BM_SkinningCpu/<method>/<threads>: one deform of the mesh: morph targets, then linear blend
//     (method 0) or dual-quaternion (1) skinning of positions, normals and tangents.
//   BM_SkinningGpu/<method>: one frame of the pass on the device mane picks (lavapipe without a
//     GPU), everything a frame pays for it: update() (joint matrices and morph weights written to
//     mapped memory, DQS's per-joint polar decompositions on the host), recording the dispatch
//     with its barriers, submit and wait for the fence. Nothing is subtracted, so on lavapipe a
//     fixed cost per submission (tens of microseconds) is spread over the vertices.
//
// Counter ns_per_vertex: wall time of the timed loop / (iterations × vertices), nanoseconds.
//
// The mesh: 20,000 vertices on a 40-joint chain (a limb-sized cylinder, 4 influences per vertex
// spread over neighbouring joints), normals and tangents, 3 morph targets with position and
// normal deltas, all three weighted non-zero in the pose; the pose bends every joint a little.
//
//   build/release/bench/mane_skinning_bench --benchmark_min_time=1

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/gtc/matrix_transform.hpp>

#include "physics/skinning.hpp"
#include "render/passes/skinning_pass.hpp"

namespace {

using namespace mane;

constexpr std::uint32_t kVertices = 20000;
constexpr std::uint32_t kJoints = 40;
constexpr std::uint32_t kInfluences = 4;
constexpr std::uint32_t kMorphTargets = 3;

physics::SkinnedMeshData limb(physics::SkinningMethod method) {
  physics::SkinnedMeshData d;
  d.influencesPerVertex = kInfluences;
  d.jointCount = kJoints;
  d.method = method;
  d.morphTargets.resize(kMorphTargets);
  constexpr std::uint32_t kAround = 50;  // vertices per ring; 400 rings
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    const float along = float(v / kAround) / float(kVertices / kAround);  // 0 … 1
    const float angle = 6.2831853f * float(v % kAround) / kAround;
    const glm::vec3 radial(0.0f, std::cos(angle), std::sin(angle));
    d.positions.push_back(glm::vec3(along, 0.0f, 0.0f) + 0.05f * radial);
    d.normals.push_back(radial);
    d.tangents.emplace_back(1.0f, 0.0f, 0.0f, 1.0f);
    // The joints around this point of the chain, weighted by distance.
    const float joint = along * float(kJoints - 1);
    const auto first = static_cast<std::uint32_t>(std::max(0.0f, std::min(joint - 1.0f, float(kJoints - kInfluences))));
    for (std::uint32_t i = 0; i < kInfluences; ++i) {
      d.joints.push_back(first + i);
      d.weights.push_back(1.0f / (0.1f + std::abs(joint - float(first + i))));
    }
    for (std::uint32_t k = 0; k < kMorphTargets; ++k) {
      d.morphTargets[k].positionDeltas.push_back(0.01f * std::sin(float(k + 1) * 7.0f * along) * radial);
      d.morphTargets[k].normalDeltas.push_back(glm::vec3(0.05f * std::cos(float(k + 1) * 7.0f * along), 0.0f, 0.0f));
    }
  }
  return d;
}

/// Every joint turned a little about its own pivot on the chain.
std::vector<glm::mat4> pose() {
  std::vector<glm::mat4> joints;
  for (std::uint32_t j = 0; j < kJoints; ++j) {
    const glm::mat4 pivot = glm::translate(glm::mat4(1.0f), glm::vec3(float(j) / (kJoints - 1), 0.0f, 0.0f));
    joints.push_back(pivot * glm::rotate(glm::mat4(1.0f), 0.02f * float(j), glm::normalize(glm::vec3(0.1f, 0.3f, 1.0f))) *
                     glm::inverse(pivot));
  }
  return joints;
}

const std::vector<float> kMorphWeights{0.5f, 0.25f, 0.8f};

render::GpuSkinnedMesh toGpu(const physics::SkinnedMeshData& d) {
  render::GpuSkinnedMesh gpu{.positions = d.positions,
                             .normals = d.normals,
                             .tangents = d.tangents,
                             .influencesPerVertex = kInfluences,
                             .joints = d.joints,
                             .weights = d.weights,
                             .jointCount = kJoints,
                             .method = d.method == physics::SkinningMethod::DualQuaternion
                                           ? render::GpuSkinningMethod::DualQuaternion
                                           : render::GpuSkinningMethod::LinearBlend};
  for (const physics::MorphTarget& target : d.morphTargets)
    gpu.morphTargets.push_back({target.positionDeltas, target.normalDeltas, target.tangentDeltas});
  return gpu;
}

/// Wall time of the timed loop, for the per-vertex counter (Google Benchmark's inverted rates print
/// in seconds).
class LoopClock {
public:
  LoopClock() : start_(std::chrono::steady_clock::now()) {}
  void setPerVertexCounter(benchmark::State& state) const {
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start_).count();
    state.counters["ns_per_vertex"] = ns / (double(state.iterations()) * kVertices);
  }

private:
  std::chrono::steady_clock::time_point start_;
};

physics::SkinningMethod methodOf(benchmark::State& state) {
  return state.range(0) == 1 ? physics::SkinningMethod::DualQuaternion : physics::SkinningMethod::LinearBlend;
}

void BM_SkinningCpu(benchmark::State& state) {
  auto mesh = physics::SkinnedMesh::create(limb(methodOf(state)));
  if (!mesh) return state.SkipWithError(mesh.error().message.c_str());
  const std::vector<glm::mat4> joints = pose();
  physics::DeformedSurface out;
  const LoopClock clock;
  for (auto _ : state) {
    if (!mesh->deform(joints, kMorphWeights, out, static_cast<unsigned>(state.range(1))))
      return state.SkipWithError("deform failed");
    benchmark::DoNotOptimize(out.positions.data());
    benchmark::ClobberMemory();
  }
  clock.setPerVertexCounter(state);
}
BENCHMARK(BM_SkinningCpu)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMicrosecond)->UseRealTime();

render::Device& device() {
  static const std::unique_ptr<render::Device> instance = [] {
    auto created = render::Device::create(render::deviceSettingsFromEnvironment());
    if (!created) {
      std::fprintf(stderr, "skinning bench: %s\n", created.error().message.c_str());
      std::exit(1);
    }
    return std::move(*created);
  }();
  return *instance;
}

void BM_SkinningGpu(benchmark::State& state) {
  auto mesh = physics::SkinnedMesh::create(limb(methodOf(state)));  // renormalised weights, as the CPU's
  if (!mesh) return state.SkipWithError(mesh.error().message.c_str());
  auto pass = render::SkinningPass::create(device(), toGpu(mesh->data()));
  if (!pass) return state.SkipWithError(pass.error().message.c_str());
  const std::vector<glm::mat4> joints = pose();
  const LoopClock clock;
  for (auto _ : state) {
    if (!(*pass)->update(joints, kMorphWeights)) return state.SkipWithError("update failed");
    device().submitAndWait([&](const vk::raii::CommandBuffer& commands) { (*pass)->record(commands); });
  }
  clock.setPerVertexCounter(state);
  state.SetLabel(device().info().name);
}
BENCHMARK(BM_SkinningGpu)->ArgsProduct({{0, 1}})->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace
