#pragma once
// Parsing the scene file's characters: the glTF file, placement, materials, skinning method,
// the clip timeline and morph weights (scenes/README.md). Errors are thrown as FieldError.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "scenes/scene.hpp"

namespace mane::scenes::detail {

CharacterInstance parseCharacter(const nlohmann::json& json, const std::string& path);

}  // namespace mane::scenes::detail
