#include "scenes/scene_ocean.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

namespace mane::scenes {

Result<std::vector<physics::HullCell>> hullCells(const Mesh& mesh, float scale, glm::ivec3 cells) {
  if (mesh.triangleCount() == 0) return fail("the hull '" + mesh.name + "' has no triangles");
  const Bounds bounds = mesh.bounds();
  const glm::vec3 size = (bounds.max - bounds.min) / glm::vec3(cells);
  std::vector<physics::HullCell> hull;
  std::vector<float> crossings;
  for (int i = 0; i < cells.x; ++i) {
    for (int k = 0; k < cells.z; ++k) {
      // The column's axis, nudged off the grid's symmetry so that it does not run along edges.
      const glm::vec2 axis(bounds.min.x + (float(i) + 0.5f + 1e-4f) * size.x,
                           bounds.min.z + (float(k) + 0.5f + 2e-4f) * size.z);
      crossings.clear();
      for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]];
        const glm::vec3 b = mesh.positions[mesh.indices[t + 1]];
        const glm::vec3 c = mesh.positions[mesh.indices[t + 2]];
        // Barycentric coordinates of the axis in the triangle's projection on y = 0.
        const float area = (b.x - a.x) * (c.z - a.z) - (c.x - a.x) * (b.z - a.z);
        if (std::abs(area) < 1e-12f) continue;
        const float u = ((b.x - axis.x) * (c.z - axis.y) - (c.x - axis.x) * (b.z - axis.y)) / area;
        const float v = ((c.x - axis.x) * (a.z - axis.y) - (a.x - axis.x) * (c.z - axis.y)) / area;
        const float w = 1.0f - u - v;
        if (u < 0.0f || v < 0.0f || w < 0.0f) continue;
        crossings.push_back(u * a.y + v * b.y + w * c.y);
      }
      std::sort(crossings.begin(), crossings.end());
      for (int j = 0; j < cells.y; ++j) {
        const float y = bounds.min.y + (float(j) + 0.5f) * size.y;
        const auto above = crossings.end() - std::upper_bound(crossings.begin(), crossings.end(), y);
        if (above % 2 == 0) continue;
        hull.push_back({.centre = glm::vec3(axis.x, y, axis.y) * scale, .size = size * scale});
      }
    }
  }
  if (hull.empty()) return fail("the hull '" + mesh.name + "' holds no cell: is it closed?");
  return hull;
}

SceneOcean::SceneOcean(const Scene& scene, physics::OceanWaves waves)
    : settings_(*scene.ocean), waves_(std::move(waves)) {
  const glm::vec2 d = glm::normalize(settings_.waves.windDirection);
  wind_ = glm::vec3(d.x, 0.0f, d.y) * settings_.waves.windSpeed;
}

Result<SceneOcean> SceneOcean::create(const Scene& scene, const Mesh* shipMesh, std::size_t shipIndex) {
  auto waves = physics::OceanWaves::create(scene.ocean->waves);
  if (!waves) return fail("ocean: " + waves.error().message);
  SceneOcean ocean(scene, std::move(*waves));
  if (!scene.ship || !shipMesh) return ocean;
  const Ship& ship = *scene.ship;
  const MeshInstance& instance = scene.meshes[shipIndex];
  const float scale = instance.transform.scale;
  auto cells = hullCells(*shipMesh, scale, ship.cells);
  if (!cells) return fail("ship: " + cells.error().message);
  // The body's origin is the hull's centre of volume, where its mass is taken to be.
  glm::dvec3 sum(0.0);
  double volume = 0.0;
  for (const physics::HullCell& cell : *cells) {
    const double v = double(cell.size.x) * cell.size.y * cell.size.z;
    sum += glm::dvec3(cell.centre) * v;
    volume += v;
  }
  const glm::vec3 centre(sum / volume);
  for (physics::HullCell& cell : *cells) cell.centre -= centre;
  const float heading = glm::radians(instance.transform.rotationDegrees.y);
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), heading, glm::vec3(0.0f, 1.0f, 0.0f));
  physics::FloatingBodySettings settings{
      .mass = ship.mass,
      .position = instance.transform.translation + glm::vec3(turn * glm::vec4(centre, 0.0f)),
      .heading = heading,
      .dragPerSecond = ship.drag,
      .hull = std::move(*cells),
      .sailCentre = ship.sailCentre * scale - centre,
      .sailArea = ship.sailArea};
  auto body = physics::FloatingBody::create(std::move(settings));
  if (!body) return fail("ship: " + body.error().message);
  ocean.ship_ = std::move(*body);
  ocean.shipIndex_ = shipIndex;
  ocean.centreOfMass_ = centre;
  ocean.shipScale_ = scale;
  ocean.foamCentre_ = {ocean.ship_->settings().position.x, ocean.ship_->settings().position.z};
  ocean.steps_.emplace(scene.simulation.stepSeconds, scene.simulation.maxStepsPerFrame);
  return ocean;
}

void SceneOcean::advance(double time, double frameDt) {
  if (!ship_) return;
  const physics::StepPlan plan = steps_->plan(frameDt);
  const double start = time - frameDt;
  for (int k = 1; k <= plan.substeps; ++k)
    ship_->step(waves_, start + plan.fractionAt(k) * frameDt, static_cast<float>(plan.fixedStep), wind_);
}

render::OceanData SceneOcean::oceanData() const {
  render::OceanData data;
  for (const physics::GerstnerWave& w : waves_.waves())
    data.waves.emplace_back(w.direction.x, w.direction.y, w.wavenumber, w.amplitude);
  data.choppiness = waves_.choppiness();
  data.grid = glm::uvec2(static_cast<std::uint32_t>(settings_.grid));
  data.reach = settings_.reach;
  data.waterColor = settings_.waterColour;
  data.fresnelPower = settings_.fresnelPower;
  data.skyColor = settings_.skyColour;
  data.fogColor = settings_.fogColour;
  data.fogDensity = settings_.fogDensity;
  data.foamColor = settings_.foamColour;
  data.foamThreshold = settings_.foamThreshold;
  data.foamHalfLife = settings_.foamHalfLife;
  data.foamGrowth = settings_.foamGrowth;
  data.foamCenter = foamCentre_;
  data.foamExtent = settings_.foamExtent;
  data.foamResolution = static_cast<std::uint32_t>(settings_.foamResolution);
  return data;
}

render::OceanFrame SceneOcean::frame(double time, float seconds) const {
  render::OceanFrame frame{.phases = std::vector<float>(waves_.waves().size()), .seconds = seconds};
  waves_.phasesAt(time, frame.phases);
  return frame;
}

glm::mat4 SceneOcean::shipBody() const {
  return ship_->transform() * glm::translate(glm::mat4(1.0f), -centreOfMass_);
}

glm::mat4 SceneOcean::shipModel() const {
  return shipBody() * glm::scale(glm::mat4(1.0f), glm::vec3(shipScale_));
}

void SceneOcean::hash(physics::StateHasher& hasher) const {
  if (ship_) hasher.addValue(ship_->state());
}

}  // namespace mane::scenes
