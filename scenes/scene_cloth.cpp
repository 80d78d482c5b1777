#include "scenes/scene_cloth.hpp"

#include <algorithm>

#include <glm/vector_relational.hpp>

#include "scenes/obj_loader.hpp"

namespace mane::scenes {
namespace {

constexpr int kGridVertices = 16;  // per side: 15 × 15 quads, fine enough to fold visibly

Mesh makeClothGrid() {
  Mesh grid;
  grid.name = "procedural:grid";
  for (int j = 0; j < kGridVertices; ++j)
    for (int i = 0; i < kGridVertices; ++i) {
      const float u = float(i) / float(kGridVertices - 1), v = float(j) / float(kGridVertices - 1);
      grid.positions.push_back({u - 0.5f, -v, 0.0f});
      grid.uvs.push_back({u, v});
    }
  for (int j = 0; j + 1 < kGridVertices; ++j)
    for (int i = 0; i + 1 < kGridVertices; ++i) {
      const std::uint32_t a = j * kGridVertices + i, b = a + 1, c = a + kGridVertices, d = c + 1;
      grid.indices.insert(grid.indices.end(), {a, c, b, b, c, d});  // counter-clockwise seen from +Z
    }
  computeSmoothNormals(grid);
  return grid;
}

}  // namespace

Result<Mesh> loadClothMesh(const Cloth& cloth, const AssetResolver& resolver,
                           const std::filesystem::path& sceneDirectory) {
  if (cloth.source == "procedural:grid") return makeClothGrid();
  auto found = resolver.lookupForScene(cloth.source, sceneDirectory);
  if (!found) return fail("cloth '" + cloth.name + "': " + found.error().message);
  if (!found->path) return fail("cloth '" + cloth.name + "': " + found->missingReason);
  auto mesh = loadMesh(*found->path);
  if (!mesh) return fail("cloth '" + cloth.name + "': " + mesh.error().message);
  return mesh;
}

Result<SceneCloth> SceneCloth::create(const Cloth& cloth, Mesh rest, const SimulationSettings& simulation,
                                      const glm::mat4& body, physics::ColliderSet colliders) {
  // Pins: the vertices on the highest row of the rest mesh, in its own space (within a
  // millionth of its height, so a flat top edge is found exactly despite rounding), the listed
  // vertices and those inside the pinned regions; each once, in vertex order.
  std::vector<bool> pin(rest.positions.size(), false);
  if (cloth.pinTopEdge && !rest.positions.empty()) {
    const Bounds bounds = rest.bounds();
    const float tolerance = 1e-6f * std::max(bounds.size().y, 1e-3f);
    for (std::uint32_t v = 0; v < rest.positions.size(); ++v)
      if (rest.positions[v].y >= bounds.max.y - tolerance) pin[v] = true;
  }
  for (std::size_t i = 0; i < cloth.pinVertices.size(); ++i) {
    const std::uint32_t v = cloth.pinVertices[i];
    if (v >= rest.positions.size())
      return fail("cloth '" + cloth.name + "': pinned.vertices[" + std::to_string(i) + "]: vertex " + std::to_string(v) +
                  " is past the mesh's " + std::to_string(rest.positions.size()) + " vertices");
    pin[v] = true;
  }
  for (const auto& [lower, upper] : cloth.pinRegions)
    for (std::size_t v = 0; v < rest.positions.size(); ++v) {
      const glm::vec3& p = rest.positions[v];
      if (glm::all(glm::greaterThanEqual(p, lower)) && glm::all(glm::lessThanEqual(p, upper))) pin[v] = true;
    }
  std::vector<std::uint32_t> pinned;
  for (std::uint32_t v = 0; v < pin.size(); ++v)
    if (pin[v]) pinned.push_back(v);
  const glm::mat4 placement = cloth.transform.matrix();
  std::vector<glm::vec3> local(rest.positions.size());
  for (std::size_t v = 0; v < local.size(); ++v) local[v] = glm::vec3(placement * glm::vec4(rest.positions[v], 1.0f));

  physics::ClothSettings settings;
  settings.solver.fixedStep = simulation.stepSeconds;
  settings.solver.maxSubstepsPerFrame = simulation.maxStepsPerFrame;
  settings.solver.constraintIterations = cloth.iterations;
  settings.solver.damping = cloth.damping;
  settings.solver.gravity = cloth.gravity;
  settings.bendingStiffness = cloth.bendingStiffness;
  auto physical = physics::Cloth::create(local, rest.indices, pinned, settings, body);
  if (!physical) return fail("cloth '" + cloth.name + "': " + physical.error().message);
  if (!colliders.empty())
    if (auto set = physical->setColliders(colliders); !set)
      return fail("cloth '" + cloth.name + "': colliders: " + set.error().message);
  SceneCloth result(std::move(*physical), std::move(rest));
  result.name_ = cloth.name;
  result.colliders_ = std::move(colliders);
  result.refreshSurface();
  return result;
}

Result<void> SceneCloth::setPinTargets(std::span<const glm::vec3> positions) {
  if (auto set = cloth_.setPinTargets(positions); !set) return fail("cloth '" + name_ + "': " + set.error().message);
  return {};
}

Result<void> SceneCloth::setColliders(physics::ColliderSet colliders) {
  if (auto set = cloth_.setColliders(colliders); !set)
    return fail("cloth '" + name_ + "': colliders: " + set.error().message);
  colliders_ = std::move(colliders);
  return {};
}

Result<void> SceneCloth::advance(const glm::mat4& body, double frameDt, unsigned threads) {
  if (auto set = cloth_.setBodyTransform(body); !set) return set;
  if (auto advanced = cloth_.advance(frameDt, threads); !advanced) return advanced;
  refreshSurface();
  return {};
}

void SceneCloth::refreshSurface() {
  surface_.positions = cloth_.particles().positions;
  computeSmoothNormals(surface_);
}

}  // namespace mane::scenes
