#pragma once
// Control cages from Wavefront OBJ, in the dialect of OpenSubdiv's regression shapes: `v`,
// `vt`, `vn` (ignored), `f` with `v`, `v/vt`, `v//vn` and `v/vt/vn` corners (1-based or
// negative, relative indices), and subdivision tags
//   t crease 2/1/0 a b sharpness        (a chain of n vertices takes 1 or n-1 sharpnesses)
//   t corner 1/1/0 v sharpness          (n vertices take 1 or n sharpnesses)
//   t interpolateboundary 1/0/0 n       (0 none, 1 edges only, 2 edges and corners)
// whose vertex indices are 0-based, as in OpenSubdiv. `o`, `g`, `s`, `usemtl`, `mtllib` and
// comments are skipped; anything else is an error rather than a silently different surface.

#include <filesystem>
#include <string_view>

#include "subdiv/cage.hpp"

namespace mane::subdiv {

/// Parses OBJ text into a validated Cage, positions in the file's units. `sourceName` names
/// the text in errors, which read "<sourceName>:<line>: <problem>" (the face, crease or
/// corner's own line when validateCage rejects the result).
[[nodiscard]] Result<Cage> parseCageObj(std::string_view text, std::string_view sourceName);

/// Reads and parses an OBJ file (see parseCageObj); errors name the file.
[[nodiscard]] Result<Cage> loadCageObj(const std::filesystem::path& file);

}  // namespace mane::subdiv
