#pragma once
// Parsing the scene file's materials: kind, textures, and the skin, fur and translucency blocks
// (scenes/README.md). Errors are thrown as FieldError, named by the JSON path, like the rest of
// the parser.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "scenes/scene.hpp"

namespace mane::scenes::detail {

Material parseMaterial(const nlohmann::json& json, const std::string& path);

}  // namespace mane::scenes::detail
