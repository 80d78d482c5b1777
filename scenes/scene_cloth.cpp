#include "scenes/scene_cloth.hpp"

#include <algorithm>
#include <cmath>

#include <glm/trigonometric.hpp>
#include <glm/vector_relational.hpp>

#include "scenes/fin_cloth.hpp"
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

/// `cape`'s cone-side sector, rows from the collar down, columns from the left front edge
/// around the back; triangles wind counter-clockwise seen from outside, their diagonals
/// alternating so that the cloth folds alike both ways.
Mesh makeCape(const CapeShape& cape) {
  Mesh mesh;
  mesh.name = "procedural:cape";
  const double flare = static_cast<double>(cape.hemRadius) - static_cast<double>(cape.collarRadius);
  const double drop = std::sqrt(std::max(0.0, double(cape.length) * double(cape.length) - flare * flare));
  const double wrap = glm::radians(static_cast<double>(cape.wrapDegrees));
  for (int row = 0; row < cape.rows; ++row) {
    const double down = double(row) / double(cape.rows - 1);
    const double radius = double(cape.collarRadius) + flare * down;
    for (int column = 0; column < cape.columns; ++column) {
      const double across = double(column) / double(cape.columns - 1);
      const double angle = wrap * (across - 0.5);
      mesh.positions.emplace_back(radius * std::sin(angle), -drop * down, -radius * std::cos(angle));
      mesh.uvs.emplace_back(across, down);
    }
  }
  for (int row = 0; row + 1 < cape.rows; ++row)
    for (int column = 0; column + 1 < cape.columns; ++column) {
      const auto a = static_cast<std::uint32_t>(row * cape.columns + column), b = a + 1;
      const auto c = a + static_cast<std::uint32_t>(cape.columns), d = c + 1;
      if ((row + column) % 2 == 0)
        mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
      else
        mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  computeSmoothNormals(mesh);
  return mesh;
}

/// `makeCape`'s vertices where the cape's pattern puts them: the cone's side unrolled into a
/// sector of a flat ring (a rectangle when the cape does not flare), so that the cloth rests flat
/// as the cut cloth does. The cone's half-angle α has sin α = flare / length; unrolled, the collar
/// lies at R₀ = collar / sin α from the apex and an angle θ around the axis becomes θ · sin α.
std::vector<glm::vec3> capePattern(const CapeShape& cape) {
  const double flare = static_cast<double>(cape.hemRadius) - static_cast<double>(cape.collarRadius);
  const double sinHalfAngle = flare / double(cape.length);
  const double apexToCollar = sinHalfAngle > 0.0 ? double(cape.collarRadius) / sinHalfAngle : 0.0;
  const double wrap = glm::radians(static_cast<double>(cape.wrapDegrees));
  std::vector<glm::vec3> pattern;
  for (int row = 0; row < cape.rows; ++row) {
    const double down = double(cape.length) * double(row) / double(cape.rows - 1);
    for (int column = 0; column < cape.columns; ++column) {
      const double angle = wrap * (double(column) / double(cape.columns - 1) - 0.5);
      if (sinHalfAngle == 0.0) {
        pattern.emplace_back(double(cape.collarRadius) * angle, -down, 0.0);
        continue;
      }
      // Measured from the collar's middle rather than the apex, which lies far off for a cape
      // that hardly flares.
      const double fromApex = apexToCollar + down, unrolled = angle * sinHalfAngle;
      pattern.emplace_back(fromApex * std::sin(unrolled), apexToCollar - fromApex * std::cos(unrolled), 0.0);
    }
  }
  return pattern;
}

}  // namespace

Result<Mesh> loadClothMesh(const Cloth& cloth, const AssetResolver& resolver,
                           const std::filesystem::path& sceneDirectory) {
  if (cloth.source == "procedural:grid") return makeClothGrid();
  if (cloth.source == "procedural:cape") return makeCape(cloth.cape);
  if (cloth.source == "procedural:fin") return makeFin(cloth.fin).mesh;
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
  // millionth of its height, so a flat top edge is found exactly despite rounding) or a fin's
  // base, the listed vertices and those inside the pinned regions; each once, in vertex order.
  const bool isFin = cloth.source == "procedural:fin";
  const FinCloth fin = isFin ? makeFin(cloth.fin) : FinCloth{};
  std::vector<bool> pin(rest.positions.size(), false);
  if (cloth.pinTopEdge && isFin) {
    for (std::uint32_t v : fin.base) pin[v] = true;
  } else if (cloth.pinTopEdge && !rest.positions.empty()) {
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
  if (cloth.source == "procedural:cape") {
    settings.pattern = capePattern(cloth.cape);
    for (glm::vec3& point : settings.pattern) point *= cloth.transform.scale;
  }
  settings.shapeHolds = fin.holds;
  settings.solver.fixedStep = simulation.stepSeconds;
  settings.solver.maxSubstepsPerFrame = simulation.maxStepsPerFrame;
  settings.solver.constraintIterations = cloth.iterations;
  settings.solver.damping = cloth.damping;
  settings.solver.gravity = cloth.gravity;
  settings.bendingStiffness = cloth.bendingStiffness;
  settings.selfCollisionThickness = cloth.selfCollision;
  if (cloth.wind) settings.wind = physics::ClothWind{.velocity = *cloth.wind, .arealDensity = cloth.arealDensity};
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
