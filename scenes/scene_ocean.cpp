#include "scenes/scene_ocean.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
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

namespace {

// Spray: drops thrown up as the hull cuts the sea, up to a few metres at the speeds a ship
// rolling in a swell meets, falling back within a second or two; a puff grows as it spreads.
constexpr physics::EffectParticleSettings kSpray{.acceleration = {0.0f, -physics::kOceanGravity, 0.0f},
                                                 .dragPerSecond = 0.4f,
                                                 .lifeSeconds = 2.5f,
                                                 .growthPerSecond = 0.25f,
                                                 .capacity = 1200};
constexpr float kSprayPerCut = 12.0f;    ///< drops per second per m/s of cut, per waterline column
constexpr float kSprayLeastCut = 0.25f;  ///< m/s: slower, the hull only laps the water
constexpr float kSprayRadius = 0.12f;    ///< metres, at birth
constexpr glm::vec3 kSprayColour{0.92f, 0.95f, 0.97f};

// Cannon smoke: blown out fast, stopped within a few metres by the air, then drifting with the
// wind, rising a little as it is warm, growing and fading over seconds.
constexpr physics::EffectParticleSettings kSmoke{.acceleration = {0.0f, 0.8f, 0.0f},
                                                 .dragPerSecond = 2.0f,
                                                 .lifeSeconds = 8.0f,
                                                 .growthPerSecond = 1.2f,
                                                 .capacity = 600};
constexpr int kPuffsPerShot = 60;
constexpr float kSmokeRadius = 1.2f;  ///< metres, at the muzzle
// Black powder's smoke is a pale grey.
constexpr glm::vec3 kSmokeColour{0.7f, 0.69f, 0.67f};

// Foam where the hull meets the sea: a faint line where the water only laps it (with the scene's
// 3 s half-life a source alone keeps 0.05·3/ln 2 ≈ 0.2 of cover, its neighbours' overlap about
// as much again), whiter where the hull cuts in.
constexpr float kWakeFoamRadius = 1.2f;      ///< metres
constexpr float kWakeFoamPerSecond = 0.05f;  ///< where the water laps the hull
constexpr float kWakeFoamPerCut = 0.5f;      ///< more per second per m/s of cut

constexpr glm::vec3 kRiggingColour{0.09f, 0.07f, 0.05f};
constexpr glm::vec3 kDebrisColour{0.33f, 0.22f, 0.12f};

float highestCrest(const physics::OceanWaves& waves) {
  float sum = 0.0f;
  for (const physics::GerstnerWave& wave : waves.waves()) sum += wave.amplitude;
  return sum;
}

float uniform(physics::SplitMix64& random, float low, float high) {
  return low + (high - low) * random.nextFloat();
}

}  // namespace

SceneOcean::SceneOcean(const Scene& scene, physics::OceanWaves waves)
    : settings_(*scene.ocean), waves_(std::move(waves)) {
  const glm::vec2 d = glm::normalize(settings_.waves.windDirection);
  wind_ = glm::vec3(d.x, 0.0f, d.y) * settings_.waves.windSpeed;
  crestHeight_ = highestCrest(waves_);
  steps_.emplace(scene.simulation.stepSeconds, scene.simulation.maxStepsPerFrame);
}

Result<SceneOcean> SceneOcean::create(const Scene& scene, const Mesh* shipMesh, std::size_t shipIndex) {
  auto waves = physics::OceanWaves::create(scene.ocean->waves);
  if (!waves) return fail("ocean: " + waves.error().message);
  SceneOcean ocean(scene, std::move(*waves));
  if (auto created = ocean.addShip(scene, shipMesh, shipIndex); !created) return std::unexpected(created.error());
  if (scene.ocean->debris) {
    physics::FloatingDebrisSettings settings = *scene.ocean->debris;
    settings.centre = ocean.foamCentre_;
    const std::optional<physics::DebrisObstacle> hull = ocean.hullObstacle();
    auto debris = physics::FloatingDebris::create(settings, ocean.waves_, 0.0, hull ? &*hull : nullptr);
    if (!debris) return fail("ocean: " + debris.error().message);
    ocean.debris_ = std::move(*debris);
  }
  return ocean;
}

Result<void> SceneOcean::addShip(const Scene& scene, const Mesh* shipMesh, std::size_t shipIndex) {
  if (!scene.ship || !shipMesh) return {};
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
  ship_ = std::move(*body);
  shipIndex_ = shipIndex;
  centreOfMass_ = centre;
  shipScale_ = scale;
  foamCentre_ = {ship_->settings().position.x, ship_->settings().position.z};
  shipScene_ = ship;
  // The ellipsoid inscribed in the hull's bounds, in its model's units; the default material's
  // albedo where it names none.
  const Bounds bounds = shipMesh->bounds();
  hullEllipsoid_ = glm::translate(glm::mat4(1.0f), 0.5f * (bounds.min + bounds.max)) *
                   glm::scale(glm::mat4(1.0f), 0.5f * (bounds.max - bounds.min));
  const auto material = std::ranges::find(scene.materials, instance.material, &Material::name);
  hullAlbedo_ = material != scene.materials.end() ? material->baseColour : Material{}.baseColour;
  // The settings are constants known to be valid.
  if (ship.spray) spray_ = *physics::EffectParticles::create(kSpray);
  if (ship.cannon) {
    smoke_ = *physics::EffectParticles::create(kSmoke);
    nextShot_ = ship.cannon->firstSeconds;
  }
  return {};
}

Result<void> SceneOcean::setWindSpeed(float speed) {
  physics::OceanSettings settings = settings_.waves;
  settings.windSpeed = speed;
  auto waves = physics::OceanWaves::create(settings);
  if (!waves) return fail("ocean: " + waves.error().message);
  waves_ = std::move(*waves);
  crestHeight_ = highestCrest(waves_);
  settings_.waves = settings;
  wind_ = glm::normalize(wind_) * speed;
  return {};
}

Result<void> SceneOcean::advance(double time, double frameDt, unsigned threads) {
  const physics::StepPlan plan = steps_->plan(frameDt);
  const double start = time - frameDt;
  const physics::TaskRunner tasks = physics::builtInTaskRunner(threads);
  Result<void> stepped;
  for (int k = 1; k <= plan.substeps; ++k) {
    // Every substep runs; the first error is the one reported.
    Result<void> substep = step(start + plan.fractionAt(k) * frameDt, static_cast<float>(plan.fixedStep), tasks);
    if (!substep && stepped) stepped = std::move(substep);
  }
  return stepped;
}

Result<void> SceneOcean::step(double time, float dt, const physics::TaskRunner& tasks) {
  Result<void> stepped;
  if (ship_) stepped = ship_->step(waves_, time, dt, wind_, tasks);
  if (spray_) {
    throwSpray(dt);
    spray_->step(dt, wind_);
    // A falling drop that reaches the sea is gone (the height under it taken at its own (x, z)
    // as the rest point: within the waves' sideways motion of the true surface). Above the
    // highest crest there is no need to ask.
    spray_->removeIf([&](const physics::EffectParticle& p) {
      return p.velocity.y < 0.0f && p.position.y < crestHeight_ &&
             p.position.y < waves_.sample({p.position.x, p.position.z}, time).position.y;
    });
  }
  if (smoke_) {
    const bool due = nextShot_ >= 0.0 && time >= nextShot_;
    if (due) {
      const float interval = shipScene_->cannon->intervalSeconds;
      nextShot_ = interval > 0.0f ? nextShot_ + interval : -1.0;
    }
    if (due || cannonFired_) shoot();
    smoke_->step(dt, wind_);
  }
  cannonFired_ = false;
  if (debris_) {
    const std::optional<physics::DebrisObstacle> hull = hullObstacle();
    debris_->step(waves_, time, dt, hull ? &*hull : nullptr);
  }
  return stepped;
}

void SceneOcean::throwSpray(float dt) {
  for (const physics::WaterlineContact& contact : ship_->waterline()) {
    if (contact.cutSpeed < kSprayLeastCut) continue;
    // Whole drops at the expected rate, the fraction by chance.
    const float expected = kSprayPerCut * contact.cutSpeed * dt;
    const int count = static_cast<int>(expected + random_.nextFloat());
    for (int i = 0; i < count; ++i) {
      // The faster the cut, the faster and higher the spray.
      const float up = contact.cutSpeed * uniform(random_, 1.5f, 3.5f);
      const float out = contact.cutSpeed * uniform(random_, 0.5f, 1.5f);
      const glm::vec3 along(-contact.outward.z, 0.0f, contact.outward.x);
      const glm::vec3 velocity =
          glm::vec3(0.0f, up, 0.0f) + out * contact.outward + uniform(random_, -0.5f, 0.5f) * out * along;
      const glm::vec3 at = contact.position + uniform(random_, -0.5f, 0.5f) * along;
      spray_->emit(at, velocity, kSprayRadius * uniform(random_, 0.6f, 1.4f));
    }
  }
}

void SceneOcean::shoot() {
  const Cannon& cannon = *shipScene_->cannon;
  const glm::mat4 body = shipBody();
  const glm::vec3 muzzle(body * glm::vec4(cannon.muzzle, 1.0f));
  const glm::vec3 aim = glm::normalize(glm::vec3(body * glm::vec4(cannon.direction, 0.0f)));
  for (int i = 0; i < kPuffsPerShot; ++i) {
    // A cone of about 10°, the puffs from slow to fast so that the blast spreads along it.
    const glm::vec3 scatter(uniform(random_, -0.18f, 0.18f), uniform(random_, -0.18f, 0.18f),
                            uniform(random_, -0.18f, 0.18f));
    const float speed = uniform(random_, 4.0f, 40.0f);
    smoke_->emit(muzzle, speed * glm::normalize(aim + scatter), kSmokeRadius * uniform(random_, 0.7f, 1.3f));
  }
}

render::EffectsFrame SceneOcean::effects() const {
  render::EffectsFrame effects;
  if (spray_) {
    for (const physics::EffectParticle& p : spray_->particles()) {
      const float fade = 1.0f - spray_->lifeShare(p);
      effects.sprites.push_back(
          {.centre = p.position, .radius = p.radius, .colour = kSprayColour, .opacity = 0.5f * fade});
    }
  }
  if (smoke_) {
    for (const physics::EffectParticle& p : smoke_->particles()) {
      const float fade = 1.0f - smoke_->lifeShare(p);
      effects.sprites.push_back({.centre = p.position,
                                 .radius = p.radius,
                                 .colour = kSmokeColour,
                                 .opacity = 0.9f * fade * fade,
                                 .underside = 0.55f});
    }
  }
  if (ship_) {
    const glm::mat4 body = shipBody();
    for (const RiggingLine& line : shipScene_->rigging)
      effects.lines.push_back({.from = glm::vec3(body * glm::vec4(line.from, 1.0f)),
                               .to = glm::vec3(body * glm::vec4(line.to, 1.0f)),
                               .width = line.width,
                               .colour = kRiggingColour});
  }
  if (debris_) {
    const std::span<const glm::vec3> corners = debris_->corners();
    for (std::size_t i = 0; i + 2 < corners.size(); i += 3)
      effects.triangles.push_back({.corners = {corners[i], corners[i + 1], corners[i + 2]}, .colour = kDebrisColour});
  }
  return effects;
}

render::OceanData SceneOcean::oceanData() const {
  render::OceanData data;
  for (const physics::GerstnerWave& w : waves_.waves())
    data.waves.emplace_back(w.direction.x, w.direction.y, w.wavenumber, w.amplitude);
  data.choppiness = waves_.choppiness();
  data.grid = glm::uvec2(settings_.grid);
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
  if (ship_) {
    // Where the hull has more contacts than the renderer takes, those that cut fastest.
    std::vector<physics::WaterlineContact> line = ship_->waterline();
    if (line.size() > render::kMaxFoamSources) {
      std::ranges::stable_sort(line, std::greater{}, &physics::WaterlineContact::cutSpeed);
      line.resize(render::kMaxFoamSources);
    }
    for (const physics::WaterlineContact& contact : line)
      frame.foamSources.emplace_back(contact.rest.x, contact.rest.y, kWakeFoamRadius,
                                     kWakeFoamPerSecond + kWakeFoamPerCut * contact.cutSpeed);
    frame.reflector =
        render::OceanReflector{.worldFromUnitSphere = hullObstacle()->worldFromUnitSphere, .albedo = hullAlbedo_};
  }
  return frame;
}

glm::mat4 SceneOcean::shipBody() const {
  return ship_->transform() * glm::translate(glm::mat4(1.0f), -centreOfMass_);
}

std::optional<physics::DebrisObstacle> SceneOcean::hullObstacle() const {
  if (!ship_) return std::nullopt;
  return physics::DebrisObstacle{.worldFromUnitSphere = shipModel() * hullEllipsoid_};
}

glm::mat4 SceneOcean::shipModel() const {
  return shipBody() * glm::scale(glm::mat4(1.0f), glm::vec3(shipScale_));
}

void SceneOcean::hash(physics::StateHasher& hasher) const {
  if (ship_) hasher.addValue(ship_->state());
  if (spray_) hasher.add(std::span(spray_->particles()));
  if (smoke_) hasher.add(std::span(smoke_->particles()));
  if (debris_) hasher.add(debris_->corners());
}

}  // namespace mane::scenes
