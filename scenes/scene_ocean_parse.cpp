#include <cmath>

#include <glm/geometric.hpp>

#include <nlohmann/json.hpp>

#include "scenes/detail/json_fields.hpp"
#include "scenes/detail/scene_ocean.hpp"

namespace mane::scenes::detail {
namespace {

void requireColour(ObjectFields& fields, const std::string& key, const glm::vec3& colour) {
  require(colour.x >= 0.0f && colour.y >= 0.0f && colour.z >= 0.0f, fields.child(key), "expected a colour ≥ 0");
}

physics::FloatingDebrisSettings parseDebris(const nlohmann::json& json, const std::string& path) {
  ObjectFields fields(json, path);
  physics::FloatingDebrisSettings debris;
  debris.pieces = fields.optional<int>("pieces", debris.pieces);
  debris.radius = fields.optional<float>("radius", debris.radius);
  debris.size = fields.optional<float>("size", debris.size);
  const int seed = fields.optional<int>("seed", static_cast<int>(debris.seed));
  fields.finish();
  require(debris.pieces >= 1 && debris.pieces <= 4096, fields.child("pieces"), "expected 1 to 4096 pieces");
  require(debris.radius >= 0.0f, fields.child("radius"), "expected metres ≥ 0");
  require(debris.size > 0.0f && debris.size <= 100.0f, fields.child("size"), "expected metres in (0, 100]");
  require(seed >= 0, fields.child("seed"), "expected a seed ≥ 0");
  debris.seed = static_cast<std::uint64_t>(seed);
  return debris;
}

RiggingLine parseRiggingLine(const nlohmann::json& json, const std::string& path) {
  ObjectFields fields(json, path);
  RiggingLine line;
  line.from = fields.required<glm::vec3>("from");
  line.to = fields.required<glm::vec3>("to");
  line.width = fields.optional<float>("width", line.width);
  fields.finish();
  require(line.from != line.to, fields.child("to"), "expected a point other than `from`");
  require(line.width > 0.0f && line.width <= 10.0f, fields.child("width"), "expected metres in (0, 10]");
  return line;
}

Cannon parseCannon(const nlohmann::json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Cannon cannon;
  cannon.muzzle = fields.required<glm::vec3>("muzzle");
  cannon.direction = fields.required<glm::vec3>("direction");
  cannon.firstSeconds = fields.optional<float>("first_seconds", cannon.firstSeconds);
  cannon.intervalSeconds = fields.optional<float>("interval_seconds", cannon.intervalSeconds);
  fields.finish();
  const float length = glm::length(cannon.direction);
  require(length > 0.0f, fields.child("direction"), "expected a direction, not zero");
  cannon.direction /= length;
  require(cannon.intervalSeconds >= 0.0f, fields.child("interval_seconds"), "expected seconds ≥ 0");
  return cannon;
}

}  // namespace

Ocean parseOcean(const nlohmann::json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Ocean ocean;
  physics::OceanSettings& waves = ocean.waves;
  waves.windSpeed = fields.optional<float>("wind_speed", waves.windSpeed);
  const glm::vec3 wind =
      fields.optional<glm::vec3>("wind_direction", glm::vec3(waves.windDirection.x, 0.0f, waves.windDirection.y));
  waves.windDirection = {wind.x, wind.z};
  waves.choppiness = fields.optional<float>("choppiness", waves.choppiness);
  waves.waveCount = fields.optional<int>("waves", waves.waveCount);
  waves.shortestWavelength = fields.optional<float>("shortest_wavelength", waves.shortestWavelength);
  const int seed = fields.optional<int>("seed", static_cast<int>(waves.seed));
  require(seed >= 0, fields.child("seed"), "expected a seed ≥ 0");
  waves.seed = static_cast<std::uint64_t>(seed);
  if (const nlohmann::json* grid = fields.take("grid")) {
    // One count for both ways, or [across, down].
    const std::string where = fields.child("grid");
    const char* expected = "expected 16 to 1024 cells, or [across, down] of 16 to 1024 each";
    require(!grid->is_array() || grid->size() == 2, where, expected);
    const glm::vec2 cells = grid->is_array() ? glm::vec2(read<float>((*grid)[0], indexPath(where, 0)),
                                                         read<float>((*grid)[1], indexPath(where, 1)))
                                             : glm::vec2(read<float>(*grid, where));
    for (int axis = 0; axis < 2; ++axis)
      require(cells[axis] == std::floor(cells[axis]) && cells[axis] >= 16.0f && cells[axis] <= 1024.0f, where,
              expected);
    ocean.grid = glm::ivec2(cells);
  }
  ocean.reach = fields.optional<float>("reach", ocean.reach);
  ocean.waterColour = fields.optional<glm::vec3>("water_colour", ocean.waterColour);
  ocean.fresnelPower = fields.optional<float>("fresnel_power", ocean.fresnelPower);
  ocean.skyColour = fields.optional<glm::vec3>("sky_colour", ocean.skyColour);
  ocean.fogColour = fields.optional<glm::vec3>("fog_colour", ocean.fogColour);
  ocean.fogDensity = fields.optional<float>("fog_density", ocean.fogDensity);
  if (const nlohmann::json* foam = fields.take("foam")) {
    ObjectFields foamFields(*foam, fields.child("foam"));
    ocean.foamColour = foamFields.optional<glm::vec3>("colour", ocean.foamColour);
    ocean.foamThreshold = foamFields.optional<float>("threshold", ocean.foamThreshold);
    ocean.foamHalfLife = foamFields.optional<float>("half_life", ocean.foamHalfLife);
    ocean.foamGrowth = foamFields.optional<float>("growth", ocean.foamGrowth);
    ocean.foamExtent = foamFields.optional<float>("extent", ocean.foamExtent);
    ocean.foamResolution = foamFields.optional<int>("resolution", ocean.foamResolution);
    foamFields.finish();
    requireColour(foamFields, "colour", ocean.foamColour);
    require(ocean.foamThreshold > -1.0f && ocean.foamThreshold < 1.0f, foamFields.child("threshold"),
            "expected a Jacobian in (−1, 1)");
    require(ocean.foamHalfLife > 0.0f, foamFields.child("half_life"), "expected seconds > 0");
    require(ocean.foamGrowth >= 0.0f, foamFields.child("growth"), "expected a rate ≥ 0 per second");
    require(ocean.foamExtent > 0.0f, foamFields.child("extent"), "expected metres > 0");
    require(ocean.foamResolution >= 16 && ocean.foamResolution <= 4096, foamFields.child("resolution"),
            "expected 16 to 4096 texels");
  }
  if (const nlohmann::json* debris = fields.take("debris")) ocean.debris = parseDebris(*debris, fields.child("debris"));
  fields.finish();
  if (auto valid = physics::validateOcean(waves); !valid) throw FieldError{path, valid.error().message};
  require(ocean.reach > 0.0f, fields.child("reach"), "expected metres > 0");
  requireColour(fields, "water_colour", ocean.waterColour);
  require(ocean.fresnelPower >= 1.0f && ocean.fresnelPower <= 5.0f, fields.child("fresnel_power"),
          "expected an exponent in [1, 5]");
  requireColour(fields, "sky_colour", ocean.skyColour);
  requireColour(fields, "fog_colour", ocean.fogColour);
  require(ocean.fogDensity >= 0.0f, fields.child("fog_density"), "expected a density ≥ 0 per metre");
  return ocean;
}

Ship parseShip(const nlohmann::json& json, const std::string& path) {
  ObjectFields fields(json, path);
  Ship ship;
  ship.mesh = fields.required<std::string>("mesh");
  ship.mass = fields.required<float>("mass");
  if (const nlohmann::json* cells = fields.take("cells")) {
    const glm::vec3 counts = read<glm::vec3>(*cells, fields.child("cells"));
    for (int axis = 0; axis < 3; ++axis)
      require(counts[axis] == std::floor(counts[axis]) && counts[axis] >= 1.0f && counts[axis] <= 64.0f,
              fields.child("cells"), "expected three whole numbers of cells, 1 to 64 each");
    ship.cells = glm::ivec3(counts);
  }
  ship.drag = fields.optional<float>("drag", ship.drag);
  ship.sailArea = fields.optional<float>("sail_area", ship.sailArea);
  ship.sailCentre = fields.optional<glm::vec3>("sail_centre", ship.sailCentre);
  ship.spray = fields.optional<bool>("spray", ship.spray);
  const nlohmann::json& rigging = fields.array("rigging", false);
  for (std::size_t i = 0; i < rigging.size(); ++i)
    ship.rigging.push_back(parseRiggingLine(rigging[i], indexPath(fields.child("rigging"), i)));
  if (const nlohmann::json* cannon = fields.take("cannon")) ship.cannon = parseCannon(*cannon, fields.child("cannon"));
  fields.finish();
  require(ship.mass > 0.0f, fields.child("mass"), "expected kilograms > 0");
  require(ship.drag >= 0.0f, fields.child("drag"), "expected a rate ≥ 0 per second");
  require(ship.sailArea >= 0.0f, fields.child("sail_area"), "expected square metres ≥ 0");
  return ship;
}

}  // namespace mane::scenes::detail
