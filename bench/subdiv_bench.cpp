// Adaptive Catmull-Clark tessellation of the LeePerrySmith head per frame, through two
// cages (the first argument of every benchmark): the scan's own triangle mesh (vertices welded
// where positions are equal, UVs kept as face-varying data), and the coarse quad-dominant cage
// nalu.json draws (scenes::coarseCageFromTriangles). Each is refined adaptively once; each frame
// tessellates again for a 1280×720 camera at three distances. A deforming-cage update (new cage
// positions → refined and local points) is timed on its own, with the tessellation, and with
// only the last tessellation's vertices re-evaluated (a still camera). BM_AnimatedHeadFrame is
// the per-frame update of a head that deforms and turns (AdaptiveTessellator::update): it keeps
// the triangles while they keep within the target in the turned view, and prepares the next
// ones on a thread of its own before they stop doing so.
//
// The summary compares, at each distance, the adaptive triangle count with what a uniform
// tessellation (every ptex face cut into a 2^k × 2^k grid of limit points) needs for the
// same maximum pixel error. Errors are measured on every 16th ptex face (the same faces for
// both), sampling each output edge at ¼, ½, ¾: the pixel distance between the straight edge
// and the limit point at the same ptex parameter. It also measures the rest pose's triangles
// moved onto the opened jaw against a fresh tessellation of it, and the worst error of the
// triangles update keeps or adopts over the turn of BM_AnimatedHeadFrame (without the jaw).
//
// BM_WorldRefineForCamera is the per-frame cost inside the World (scenes::World::
// refineForCamera): the same head as a scene mesh with a `subdivision` block, turning ±20° at
// 0.25 Hz, so every frame sees it from a new side: tessellated again when the kept triangles
// no longer keep within the target, then copied into the mesh the renderer's replaceMesh reads.
//
// BM_ElbowTubeFrame is a skinned cage bending (scenes::SkinnedCage, Timbury's elbow): an open
// tube of 8 × 12 quads, 10 cm across and 60 cm long, on two joints blended over its middle third,
// its elbow sweeping 0° → 90° → 0° over 120 frames; each frame skins the cage, moves the limit
// surface and tessellates it again for a still 1280×720 camera from the side.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/assets.hpp"
#include "scenes/gltf_loader.hpp"
#include "scenes/scene.hpp"
#include "scenes/skinned_cage.hpp"
#include "scenes/subdivided_mesh.hpp"
#include "scenes/world.hpp"
#include "subdiv/limit.hpp"
#include "subdiv/tessellator.hpp"

namespace mane {
namespace {

constexpr glm::vec2 kViewport{1280.0f, 720.0f};
// Camera distances from the head's centre in the file's units (the head is ~8 units tall):
// filling the screen, about two thirds of its height, about a seventh of it.
constexpr float kDistances[] = {12.0f, 30.0f, 80.0f};
constexpr const char* kDistanceNames[] = {"near", "mid", "far"};
constexpr int kErrorSampleStride = 16;

struct Head {
  std::string problem;
  subdiv::Cage cage;
  std::unique_ptr<subdiv::LimitSurface> surface;
  std::unique_ptr<subdiv::AdaptiveTessellator> tessellator;
  std::vector<std::vector<glm::vec3>> poses;  ///< deformed cages, alternated per frame
  glm::vec3 centre{0.0f};
};

/// The scan's own triangles as the cage, or the coarse cage nalu.json draws (kCoarseCage).
enum class CageKind { kScan, kCoarse };
constexpr scenes::MeshSimplification kCoarseCage{.triangles = 3000, .maxRelativeError = 0.05f};
constexpr int kCoarseIsolation = 1;

Head loadHead(CageKind kind) {
  Head head;
  auto resolver = scenes::AssetResolver::createDefault();
  if (!resolver) return {.problem = resolver.error().message};
  auto found = resolver->lookup("head/LeePerrySmith/LeePerrySmith.glb");
  if (!found || !found->path) return {.problem = found ? found->missingReason : found.error().message};
  auto mesh = scenes::loadGltf(*found->path);
  if (!mesh) return {.problem = mesh.error().message};
  head.centre = mesh->bounds().centre();
  int isolation = kCoarseIsolation;
  if (kind == CageKind::kCoarse) {
    auto coarse = scenes::coarseCageFromTriangles(*mesh, kCoarseCage);
    if (!coarse) return {.problem = coarse.error().message};
    head.cage = std::move(coarse->cage);
  } else {
    head.cage = scenes::cageFromTriangles(*mesh);
    // Isolation level 1: every vertex of a triangle cage is extraordinary after one step, so
    // each level multiplies the Gregory end caps' local points (and the update time).
    isolation = 1;
  }
  auto surface = subdiv::LimitSurface::create(head.cage, {.maxIsolationLevel = isolation});
  if (!surface) return {.problem = surface.error().message};
  head.surface = std::make_unique<subdiv::LimitSurface>(std::move(*surface));
  auto tessellator = subdiv::AdaptiveTessellator::create(*head.surface);
  if (!tessellator) return {.problem = tessellator.error().message};
  head.tessellator = std::make_unique<subdiv::AdaptiveTessellator>(std::move(*tessellator));
  // A jaw-like deformation: points below the centre swing about the x axis by ±3°.
  for (float angle : {0.05f, -0.05f}) {
    std::vector<glm::vec3> pose = head.cage.positions;
    for (glm::vec3& p : pose) {
      const float weight = std::clamp((head.centre.y - p.y) / 4.0f, 0.0f, 1.0f);
      const float a = angle * weight;
      const glm::vec3 d = p - head.centre;
      p = head.centre + glm::vec3(d.x, d.y * std::cos(a) - d.z * std::sin(a), d.y * std::sin(a) + d.z * std::cos(a));
    }
    head.poses.push_back(std::move(pose));
  }
  return head;
}

Head& head(CageKind kind) {
  static Head scan = loadHead(CageKind::kScan);
  static Head coarse = loadHead(CageKind::kCoarse);
  return kind == CageKind::kScan ? scan : coarse;
}

/// The cage a benchmark's first argument names.
Head& headFor(const benchmark::State& state) {
  return head(CageKind(state.range(0)));
}

subdiv::ScreenView viewAt(const Head& at, float distance) {
  const glm::mat4 projection = glm::perspective(glm::radians(40.0f), kViewport.x / kViewport.y, 0.1f, 1000.0f);
  const glm::vec3 eye = at.centre + glm::vec3(0.0f, 0.0f, distance);
  return {projection * glm::lookAt(eye, at.centre, glm::vec3(0.0f, 1.0f, 0.0f)), kViewport};
}

bool skipWithoutHead(benchmark::State& state) {
  if (headFor(state).problem.empty()) return false;
  state.SkipWithError(headFor(state).problem.c_str());
  return true;
}

// Arguments: CageKind, distance index, worker threads.
void BM_AdaptiveFrame(benchmark::State& state) {
  if (skipWithoutHead(state)) return;
  Head& head = headFor(state);
  const subdiv::ScreenView view = viewAt(head, kDistances[state.range(1)]);
  const auto threads = static_cast<unsigned>(state.range(2));
  subdiv::TessellatedMesh mesh;
  for (auto _ : state) {
    head.tessellator->tessellate(view, mesh, threads);
    benchmark::DoNotOptimize(mesh.indices.data());
  }
  state.SetLabel(kDistanceNames[state.range(1)]);
  state.counters["triangles"] = double(mesh.triangleCount());
  state.counters["cells"] = double(head.tessellator->statistics().cells);
}
BENCHMARK(BM_AdaptiveFrame)
    ->ArgsProduct({{0, 1}, {0, 1, 2}, {1, 2}})
    ->ArgNames({"cage", "view", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Arguments: CageKind, worker threads.
void BM_DeformingCageUpdate(benchmark::State& state) {
  if (skipWithoutHead(state)) return;
  Head& head = headFor(state);
  const auto threads = static_cast<unsigned>(state.range(1));
  std::size_t frame = 0;
  for (auto _ : state) {
    auto updated = head.surface->updatePositions(head.poses[frame++ % 2], threads);
    benchmark::DoNotOptimize(updated);
  }
  state.counters["points"] = double(head.surface->controlPointCount());
}
BENCHMARK(BM_DeformingCageUpdate)
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->ArgNames({"cage", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Arguments: CageKind, distance index, worker threads.
void BM_DeformAndTessellateFrame(benchmark::State& state) {
  if (skipWithoutHead(state)) return;
  Head& head = headFor(state);
  const subdiv::ScreenView view = viewAt(head, kDistances[state.range(1)]);
  const auto threads = static_cast<unsigned>(state.range(2));
  subdiv::TessellatedMesh mesh;
  std::size_t frame = 0;
  for (auto _ : state) {
    auto updated = head.surface->updatePositions(head.poses[frame++ % 2], threads);
    benchmark::DoNotOptimize(updated);
    head.tessellator->tessellate(view, mesh, threads);
    benchmark::DoNotOptimize(mesh.indices.data());
  }
  state.SetLabel(kDistanceNames[state.range(1)]);
  state.counters["triangles"] = double(mesh.triangleCount());
}
BENCHMARK(BM_DeformAndTessellateFrame)
    ->ArgsProduct({{0, 1}, {0, 1, 2}, {1, 2}})
    ->ArgNames({"cage", "view", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Arguments: CageKind, distance index, worker threads. A deforming head seen from a still
// camera: each frame moves the cage and re-evaluates the last tessellation's vertices
// (AdaptiveTessellator::updateVertices) instead of tessellating again.
void BM_DeformAndUpdateVerticesFrame(benchmark::State& state) {
  if (skipWithoutHead(state)) return;
  Head& head = headFor(state);
  const subdiv::ScreenView view = viewAt(head, kDistances[state.range(1)]);
  const auto threads = static_cast<unsigned>(state.range(2));
  subdiv::TessellatedMesh mesh;
  head.tessellator->tessellate(view, mesh, threads);
  std::size_t frame = 0;
  for (auto _ : state) {
    auto updated = head.surface->updatePositions(head.poses[frame++ % 2], threads);
    auto moved = head.tessellator->updateVertices(mesh, threads);
    if (!updated || !moved) return state.SkipWithError("updating the head failed");
    benchmark::DoNotOptimize(mesh.positions.data());
  }
  state.SetLabel(kDistanceNames[state.range(1)]);
  state.counters["triangles"] = double(mesh.triangleCount());
}
BENCHMARK(BM_DeformAndUpdateVerticesFrame)
    ->ArgsProduct({{0, 1}, {0, 1, 2}, {1, 2}})
    ->ArgNames({"cage", "view", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Frames of one animation cycle: 60 per second over one 4 s period of the turn.
constexpr int kCycleFrames = 240;

/// `view` with the head turned as in frame `frame` of the cycle: ±20° at 0.25 Hz, 60 frames a
/// second, about a vertical axis a unit behind the head's centre (the neck).
subdiv::ScreenView turnedAtFrame(const Head& head, subdiv::ScreenView view, int frame) {
  const glm::vec3 neck = head.centre - glm::vec3(0.0f, 0.0f, 1.0f);
  const float degrees = 20.0f * std::sin(2.0f * 3.14159265f * 0.25f * float(frame) / 60.0f);
  view.viewProjection = view.viewProjection * glm::translate(glm::mat4(1.0f), neck) *
                        glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0)) *
                        glm::translate(glm::mat4(1.0f), -neck);
  return view;
}

// Arguments: CageKind, distance index, worker threads, prepared, paced. The animated head, one
// frame per iteration over one cycle: the jaw moves (the cage deforms, as above) while the head
// turns ±20° at 0.25 Hz about a vertical axis a unit behind its centre (the neck). Each frame
// moves the cage, then keeps the triangles (re-evaluating their moved vertices) while they keep
// within the target in the turned view. Prepared (1): AdaptiveTessellator::update, which
// prepares the next tessellation on a thread of its own before they stop doing so and adopts it
// five frames later; else (0) the frame tessellates again itself when they stop. Paced (1),
// frames start every 1/60 s as in an application, so a preparing thread has the rest of each
// frame; back to back (0), it competes with the frames, which may wait for it. The time is the
// mean of the frames' updates (the pacing's waits left out); `p90_ms` the time nine frames in
// ten stay within, `worst_ms` the slowest, `retessellated` the share of frames that
// tessellated on the calling threads, and `prepared` the share that started a preparation.
void BM_AnimatedHeadFrame(benchmark::State& state) {
  if (skipWithoutHead(state)) return;
  Head& head = headFor(state);
  const subdiv::ScreenView still = viewAt(head, kDistances[state.range(1)]);
  const auto threads = static_cast<unsigned>(state.range(2));
  const bool prepare = state.range(3) != 0;
  const bool paced = state.range(4) != 0;
  const auto viewAtFrame = [&](int frame) { return turnedAtFrame(head, still, frame); };
  // From the rest pose, whatever the benchmarks before left.
  if (!head.surface->updatePositions(head.cage.positions)) return state.SkipWithError("restoring the head failed");
  auto tessellator = subdiv::AdaptiveTessellator::create(*head.surface);
  if (!tessellator) return state.SkipWithError(tessellator.error().message.c_str());
  subdiv::TessellatedMesh mesh;
  // The first frame as World makes it (update's first call also warms the preparing thread's storage).
  if (prepare) {
    if (!tessellator->update(viewAtFrame(0), mesh, threads)) return state.SkipWithError("the first update failed");
  } else {
    tessellator->tessellate(viewAtFrame(0), mesh, threads);
  }
  int frame = 0, retessellated = 0, prepared = 0;
  std::vector<double> frameMs;
  frameMs.reserve(kCycleFrames);
  const auto cycleStart = std::chrono::steady_clock::now();
  for (auto _ : state) {
    ++frame;
    if (paced) std::this_thread::sleep_until(cycleStart + std::chrono::microseconds(frame * 1000000 / 60));
    const auto start = std::chrono::steady_clock::now();
    auto updated = head.surface->updatePositions(head.poses[std::size_t(frame % 2)], threads);
    if (!updated) return state.SkipWithError("updating the head failed");
    const subdiv::ScreenView view = viewAtFrame(frame);
    Result<subdiv::FrameUpdate> update = subdiv::FrameUpdate::kKept;
    if (prepare) {
      update = tessellator->update(view, mesh, threads);
    } else if (tessellator->keepsTarget(view)) {
      if (auto moved = tessellator->updateVertices(mesh, threads); !moved) update = std::unexpected(moved.error());
    } else {
      tessellator->tessellate(view, mesh, threads);
      update = subdiv::FrameUpdate::kTessellated;
    }
    if (!update) return state.SkipWithError(update.error().message.c_str());
    retessellated += *update == subdiv::FrameUpdate::kTessellated ? 1 : 0;
    prepared += *update == subdiv::FrameUpdate::kPrepared ? 1 : 0;
    benchmark::DoNotOptimize(mesh.positions.data());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds);
    frameMs.push_back(1000.0 * seconds);
  }
  state.SetLabel(kDistanceNames[state.range(1)]);
  state.counters["triangles"] = double(mesh.triangleCount());
  std::sort(frameMs.begin(), frameMs.end());
  state.counters["p90_ms"] = frameMs.empty() ? 0.0 : frameMs[frameMs.size() * 9 / 10];
  state.counters["worst_ms"] = frameMs.empty() ? 0.0 : frameMs.back();
  state.counters["retessellated"] = double(retessellated) / double(frame);
  state.counters["prepared"] = double(prepared) / double(frame);
}
BENCHMARK(BM_AnimatedHeadFrame)
    ->ArgsProduct({{0, 1}, {0, 1, 2}, {1, 2}, {0, 1}, {0, 1}})
    ->ArgNames({"cage", "view", "threads", "prepared", "paced"})
    ->Iterations(kCycleFrames)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

// A nalu-like scene: the head (0.025 m per file unit) with either cage as above, turning ±20° at
// 0.25 Hz, no hair; the camera at the mid distance (30 units = 0.75 m) from the head's centre.
std::unique_ptr<scenes::World> loadTurningHead(CageKind kind) {
  if (!head(kind).problem.empty()) return nullptr;
  const glm::vec3 centre = head(kind).centre * 0.025f;
  const std::string subdivision =
      kind == CageKind::kScan ? R"({"isolation": 1})"
                              : R"({"isolation": )" + std::to_string(kCoarseIsolation) +
                                    R"(, "coarse_cage": {"triangles": )" + std::to_string(kCoarseCage.triangles) +
                                    R"(, "max_error": )" + std::to_string(kCoarseCage.maxRelativeError) + "}}";
  const std::string text = R"({"name": "turning head", "output": {"width": 1280, "height": 720},
      "camera": {"position": [)" +
                           std::to_string(centre.x) + ", " + std::to_string(centre.y) + ", " +
                           std::to_string(centre.z + 0.75f) + R"(], "target": [)" + std::to_string(centre.x) + ", " +
                           std::to_string(centre.y) + ", " + std::to_string(centre.z) +
                           R"(], "fov_degrees": 40, "near": 0.01, "far": 10},
      "meshes": [{"name": "head", "source": "head/LeePerrySmith/LeePerrySmith.glb", "transform": {"scale": 0.025},
                  "subdivision": )" +
                           subdivision + R"(}],
      "animation": {"head": {"mesh": "head", "motion": "turn", "amplitude_degrees": 20, "frequency_hz": 0.25}}})";
  auto scene = scenes::parseScene(text, "turning_head.json");
  if (!scene) return nullptr;
  auto resolver = scenes::AssetResolver::createDefault();
  if (!resolver) return nullptr;
  auto world = scenes::World::create(std::move(*scene), *resolver, {.loadTextures = false});
  if (!world) return nullptr;
  return std::make_unique<scenes::World>(std::move(*world));
}

// Arguments: CageKind, worker threads.
void BM_WorldRefineForCamera(benchmark::State& state) {
  if (skipWithoutHead(state)) return;
  static const std::unique_ptr<scenes::World> worlds[] = {loadTurningHead(CageKind::kScan),
                                                          loadTurningHead(CageKind::kCoarse)};
  const std::unique_ptr<scenes::World>& world = worlds[state.range(0)];
  if (!world) {
    state.SkipWithError("the turning-head scene did not load");
    return;
  }
  const auto threads = static_cast<unsigned>(state.range(1));
  const render::Camera camera = world->frameInput().camera;
  std::size_t triangles = 0, changed = 0, frames = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto advanced = world->advance(1.0 / 60.0, 1);  // nothing simulated: the clock and the head
    state.ResumeTiming();
    auto refined = world->refineForCamera(camera, {1280, 720}, threads);
    if (!advanced || !refined) {
      state.SkipWithError("refineForCamera failed");
      return;
    }
    changed += refined->size();
    ++frames;
    triangles = world->meshData(0).indices.size() / 3;
  }
  state.SetLabel("mid, turning");
  state.counters["triangles"] = double(triangles);
  state.counters["retessellated"] = double(changed) / double(std::max<std::size_t>(frames, 1));
}
BENCHMARK(BM_WorldRefineForCamera)
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->ArgNames({"cage", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The elbow tube (the same shape as tests/scenes/skinned_cage_tests.cpp): rings of 8 vertices,
// radius 5 cm, every 5 cm along +y; joint 1's weight rises smoothly from ring 4 to ring 8.
constexpr int kTubeAround = 8;
constexpr int kTubeAlong = 12;
constexpr float kTubeRadius = 0.05f;
constexpr float kTubeLength = 0.6f;
constexpr int kElbowSweepFrames = 120;

std::unique_ptr<scenes::SkinnedCage> makeElbowTube() {
  subdiv::Cage cage;
  physics::SkinnedMeshData skin{
      .influencesPerVertex = 2, .jointCount = 2, .method = physics::SkinningMethod::DualQuaternion};
  for (int r = 0; r <= kTubeAlong; ++r) {
    const float t = std::clamp(float(r - 4) / 4.0f, 0.0f, 1.0f);
    const float upper = t * t * (3.0f - 2.0f * t);
    for (int s = 0; s < kTubeAround; ++s) {
      const float angle = 2.0f * 3.14159265f * float(s) / float(kTubeAround);
      cage.positions.emplace_back(kTubeRadius * std::sin(angle), kTubeLength * float(r) / float(kTubeAlong),
                                  kTubeRadius * std::cos(angle));
      skin.joints.insert(skin.joints.end(), {0u, 1u});
      skin.weights.insert(skin.weights.end(), {1.0f - upper, upper});
    }
  }
  const auto at = [](int r, int s) { return std::uint32_t(r * kTubeAround + s % kTubeAround); };
  for (int r = 0; r < kTubeAlong; ++r)
    for (int s = 0; s < kTubeAround; ++s) {
      cage.faceSizes.push_back(4);
      cage.faceVertices.insert(cage.faceVertices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)});
    }
  auto tube = scenes::SkinnedCage::create(std::move(cage), std::move(skin), {});
  return tube ? std::move(*tube) : nullptr;
}

/// The elbow's joints at `frame` of the sweep: joint 1 turned about z through the tube's middle.
std::array<glm::mat4, 2> elbowAtFrame(int frame) {
  const float phase = float(frame % kElbowSweepFrames) / float(kElbowSweepFrames);
  const float degrees = 90.0f * (1.0f - std::abs(2.0f * phase - 1.0f));
  const glm::vec3 elbow(0.0f, 0.5f * kTubeLength, 0.0f);
  return {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), elbow) *
                               glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 0, 1)) *
                               glm::translate(glm::mat4(1.0f), -elbow)};
}

// Arguments: camera distance in cm (100: the whole tube in view, ~100 px wide; 30: the elbow
// fills the frame), worker threads. One frame per iteration: pose, then tessellate (every pose moves the cage, so
// every frame tessellates). `triangles` is the mean count over the sweep.
void BM_ElbowTubeFrame(benchmark::State& state) {
  const std::unique_ptr<scenes::SkinnedCage> tube = makeElbowTube();
  if (!tube) return state.SkipWithError("the elbow tube did not build");
  const float distance = float(state.range(0)) / 100.0f;
  const auto threads = static_cast<unsigned>(state.range(1));
  const glm::vec3 target(-0.05f, 0.3f, 0.0f);
  const glm::mat4 view = glm::perspective(glm::radians(40.0f), kViewport.x / kViewport.y, 0.01f, 10.0f) *
                         glm::lookAt(target + glm::vec3(0.0f, 0.0f, distance), target, glm::vec3(0.0f, 1.0f, 0.0f));
  scenes::Mesh mesh;
  std::vector<float> inverseRadius;
  int frame = 0;
  double triangles = 0.0;
  for (auto _ : state) {
    const auto joints = elbowAtFrame(++frame);
    auto posed = tube->pose(joints, {}, threads);
    if (!posed) return state.SkipWithError(posed.error().message.c_str());
    tube->tessellate(view, kViewport, mesh, inverseRadius, threads);
    benchmark::DoNotOptimize(mesh.indices.data());
    triangles += double(mesh.triangleCount());
  }
  state.SetLabel(state.range(0) >= 100 ? "side" : "close");
  state.counters["triangles"] = triangles / double(std::max(frame, 1));
}
BENCHMARK(BM_ElbowTubeFrame)
    ->ArgsProduct({{100, 30}, {1, 2}})
    ->ArgNames({"distance_cm", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

glm::dvec2 toPixels(const subdiv::ScreenView& view, const glm::dvec3& p) {
  const glm::dvec4 clip = glm::dmat4(view.viewProjection) * glm::dvec4(p, 1.0);
  return (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * glm::dvec2(view.viewportSize);
}

/// Pixel error of the straight edge a–b (ptex coordinates ua, ub of `face`) against the
/// limit surface, sampled at ¼, ½, ¾.
double edgeError(const Head& head, const subdiv::ScreenView& view, std::uint32_t face, const glm::dvec3& a,
                 const glm::dvec3& b, glm::dvec2 ua, glm::dvec2 ub) {
  double worst = 0.0;
  for (double f : {0.25, 0.5, 0.75}) {
    const glm::dvec2 uv = glm::mix(ua, ub, f);
    const glm::dvec3 onSurface = head.surface->evaluatePosition(face, uv.x, uv.y);
    worst = std::max(worst, glm::length(toPixels(view, glm::mix(a, b, f)) - toPixels(view, onSurface)));
  }
  return worst;
}

double adaptiveError(const Head& head, const subdiv::ScreenView& view, const subdiv::TessellatedMesh& mesh) {
  double worst = 0.0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    if (mesh.trianglePtexFaces[t] % kErrorSampleStride != 0) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t a = 3 * t + k, b = 3 * t + (k + 1) % 3;
      worst = std::max(worst,
                       edgeError(head, view, mesh.trianglePtexFaces[t], glm::dvec3(mesh.positions[mesh.indices[a]]),
                                 glm::dvec3(mesh.positions[mesh.indices[b]]), glm::dvec2(mesh.cornerPtexCoordinates[a]),
                                 glm::dvec2(mesh.cornerPtexCoordinates[b])));
    }
  }
  return worst;
}

/// The error of cutting every ptex face into an n × n grid (two triangles per cell).
double uniformError(const Head& head, const subdiv::ScreenView& view, int n) {
  double worst = 0.0;
  std::vector<glm::dvec3> grid(std::size_t((n + 1) * (n + 1)));
  for (std::uint32_t face = 0; face < head.surface->ptexFaceCount(); face += kErrorSampleStride) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        grid[std::size_t(j * (n + 1) + i)] = head.surface->evaluatePosition(face, double(i) / n, double(j) / n);
    const auto at = [&](int i, int j) { return grid[std::size_t(j * (n + 1) + i)]; };
    const auto uv = [&](int i, int j) { return glm::dvec2(double(i) / n, double(j) / n); };
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        if (i < n) worst = std::max(worst, edgeError(head, view, face, at(i, j), at(i + 1, j), uv(i, j), uv(i + 1, j)));
        if (j < n) worst = std::max(worst, edgeError(head, view, face, at(i, j), at(i, j + 1), uv(i, j), uv(i, j + 1)));
        if (i < n && j < n)
          worst = std::max(worst, edgeError(head, view, face, at(i, j), at(i + 1, j + 1), uv(i, j), uv(i + 1, j + 1)));
      }
  }
  return worst;
}

void printSummary(CageKind kind) {
  const Head& head = mane::head(kind);
  if (!head.problem.empty()) return;
  std::size_t quads = 0;
  for (const std::uint32_t size : head.cage.faceSizes) quads += size == 4 ? 1 : 0;
  std::fprintf(stderr,
               "\nLeePerrySmith %s cage: %zu vertices, %zu faces (%zu quads), %u ptex faces, %zu patches, %zu points\n",
               kind == CageKind::kScan ? "scan" : "coarse", head.cage.positions.size(), head.cage.faceSizes.size(),
               quads, head.surface->ptexFaceCount(), head.surface->patchCount(), head.surface->controlPointCount());
  std::fprintf(stderr, "%-5s %10s %9s %12s %12s %7s\n", "view", "adaptive", "max px", "uniform grid", "uniform tris",
               "ratio");
  auto tessellator = subdiv::AdaptiveTessellator::create(*head.surface, {.keepPtexCoordinates = true});
  if (!tessellator || !head.surface->updatePositions(head.cage.positions)) return;  // the rest pose
  for (int d = 0; d < 3; ++d) {
    const subdiv::ScreenView view = viewAt(head, kDistances[d]);
    subdiv::TessellatedMesh mesh;
    tessellator->tessellate(view, mesh);
    const double target = adaptiveError(head, view, mesh);
    int n = 1;
    while (n < 32 && uniformError(head, view, n) > target) n *= 2;  // 32 × 32 at most: slow to measure
    const double uniformTriangles = 2.0 * n * n * head.surface->ptexFaceCount();
    std::fprintf(stderr, "%-5s %10zu %9.3f %9d×%-2d %12.0f %7.3f\n", kDistanceNames[d], mesh.triangleCount(), target, n,
                 n, uniformTriangles, double(mesh.triangleCount()) / uniformTriangles);
  }
  // The jaw opened by 3° (one of the deforming frames' poses) under the mid view: the rest
  // pose's triangles moved onto the new surface, against a fresh tessellation of it.
  const subdiv::ScreenView view = viewAt(head, kDistances[1]);
  subdiv::TessellatedMesh kept, fresh;
  tessellator->tessellate(view, kept);
  if (!head.surface->updatePositions(head.poses[0]) || !tessellator->updateVertices(kept)) return;
  const double keptError = adaptiveError(head, view, kept);
  tessellator->tessellate(view, fresh);
  const double freshError = adaptiveError(head, view, fresh);
  std::fprintf(stderr, "jaw at 3°, mid view: rest pose's triangles moved %.3f px, tessellated again %.3f px\n",
               keptError, freshError);
  if (!head.surface->updatePositions(head.cage.positions)) return;

  // The turn alone, through AdaptiveTessellator::update: the worst error of the triangles it
  // kept or adopted (every 4th frame measured), and how many frames prepared a tessellation or
  // tessellated on the calling thread.
  for (int d = 0; d < 3; ++d) {
    const subdiv::ScreenView still = viewAt(head, kDistances[d]);
    tessellator->tessellate(turnedAtFrame(head, still, 0), kept);
    int retessellated = 0, prepared = 0;
    double worstKept = 0.0;
    for (int frame = 1; frame <= kCycleFrames; ++frame) {
      const subdiv::ScreenView turned = turnedAtFrame(head, still, frame);
      const auto update = tessellator->update(turned, kept);
      if (!update) return;
      retessellated += *update == subdiv::FrameUpdate::kTessellated ? 1 : 0;
      prepared += *update == subdiv::FrameUpdate::kPrepared ? 1 : 0;
      if (*update != subdiv::FrameUpdate::kTessellated && frame % 4 == 0)
        worstKept = std::max(worstKept, adaptiveError(head, turned, kept));
    }
    std::fprintf(stderr,
                 "turning, %s view: %d of %d frames prepared a tessellation, %d tessellated on the calling thread; "
                 "kept and adopted triangles at most %.3f px\n",
                 kDistanceNames[d], prepared, kCycleFrames, retessellated, worstKept);
  }
}

}  // namespace
}  // namespace mane

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  mane::printSummary(mane::CageKind::kScan);
  mane::printSummary(mane::CageKind::kCoarse);
  benchmark::Shutdown();
  return 0;
}
