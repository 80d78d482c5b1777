#pragma once
// Parsing the scene file's "ocean" and "ship" blocks (scenes/README.md#ocean). Errors are
// thrown as FieldError, named by the JSON path, like the rest of the parser.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "scenes/scene.hpp"

namespace mane::scenes::detail {

Ocean parseOcean(const nlohmann::json& json, const std::string& path);
Ship parseShip(const nlohmann::json& json, const std::string& path);

}  // namespace mane::scenes::detail
