#pragma once
// Built-in meshes: the stand-ins used when an asset is missing, and test geometry.

#include "scenes/mesh.hpp"

namespace mane::scenes {

/// A UV sphere centred on the origin, radius in metres. `rings` ≥ 2 latitude bands from
/// pole (+Y) to pole, `segments` ≥ 3 longitude slices; smaller values are raised to these.
/// The seam column is duplicated so UVs run 0..1 without wrapping: (rings + 1) *
/// (segments + 1) vertices and 2 * segments * (rings - 1) triangles (one per pole slice;
/// the pole rows keep a copy per column, of which one at each pole goes unused).
/// Normals are the exact unit radial directions; u grows eastward around +Y, v from 0 at
/// the north pole to 1 at the south pole. Triangles wind counter-clockwise seen from outside.
[[nodiscard]] Mesh makeSphere(int rings, int segments, float radius);

}  // namespace mane::scenes
