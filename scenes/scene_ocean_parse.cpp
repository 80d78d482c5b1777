#include <cmath>

#include <nlohmann/json.hpp>

#include "scenes/detail/json_fields.hpp"
#include "scenes/detail/scene_ocean.hpp"

namespace mane::scenes::detail {
namespace {

void requireColour(ObjectFields& fields, const std::string& key, const glm::vec3& colour) {
  require(colour.x >= 0.0f && colour.y >= 0.0f && colour.z >= 0.0f, fields.child(key), "expected a colour ≥ 0");
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
  ocean.grid = fields.optional<int>("grid", ocean.grid);
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
  fields.finish();
  if (auto valid = physics::validateOcean(waves); !valid) throw FieldError{path, valid.error().message};
  require(ocean.grid >= 16 && ocean.grid <= 1024, fields.child("grid"), "expected 16 to 1024 cells");
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
  fields.finish();
  require(ship.mass > 0.0f, fields.child("mass"), "expected kilograms > 0");
  require(ship.drag >= 0.0f, fields.child("drag"), "expected a rate ≥ 0 per second");
  require(ship.sailArea >= 0.0f, fields.child("sail_area"), "expected square metres ≥ 0");
  return ship;
}

}  // namespace mane::scenes::detail
