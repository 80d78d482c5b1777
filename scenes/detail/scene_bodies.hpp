#pragma once
// Parsing the scene file's bodies: placements, grooms (with their colliders, simulation and
// render blocks), cloths, and the scene's hair shadows (scenes/README.md).
// Errors are thrown as FieldError, named by the JSON path, like the rest of the parser.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "render/hair_data.hpp"
#include "scenes/scene.hpp"

namespace mane::scenes::detail {

Transform parseTransform(const nlohmann::json& json, const std::string& path);
/// A mesh's (or character's) "subdivision" block.
Subdivision parseSubdivision(const nlohmann::json& json, const std::string& path);
Groom parseGroom(const nlohmann::json& json, const std::string& path);
Cloth parseCloth(const nlohmann::json& json, const std::string& path);
Glasses parseGlasses(const nlohmann::json& json, const std::string& path);
render::HairShadowSettings parseHairShadows(const nlohmann::json& json, const std::string& path);
/// The scene's "post" block: tone mapping, auto gain, key, glow, adaptation time.
render::PostSettings parsePost(const nlohmann::json& json, const std::string& path);

}  // namespace mane::scenes::detail
