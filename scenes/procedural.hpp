#pragma once
// Built-in meshes: the stand-ins used when an asset is missing, and test geometry (the test
// objects of the voxelized-translucency paper among them, docs/design.md#sources).
//
// Every mesh here is closed by position: vertices duplicated for UV seams and poles repeat
// their twin's position bit for bit, so each directed edge a→b is matched by b→a when a and b
// are compared by position (what render/luts/solid_voxels.hpp checks before voxelizing).

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

/// The cube [−halfSide, halfSide]³ with a spherical hollow of `hollowRadius` (< halfSide) at its
/// centre: the voxelized-translucency paper's test of hollows in translucency. The cube has 4
/// vertices and 2 triangles per face, flat normals, UVs 0..1 per face, and winds counter-clockwise
/// seen from outside. The hollow is `makeSphere(hollowRings, hollowSegments, hollowRadius)` turned
/// inside out: its triangles wind inward and its normals point into the hollow, away from the
/// material, so the whole surface bounds the material the way solid_voxels.hpp expects. Cube
/// vertices come first (24), then the hollow's.
[[nodiscard]] Mesh makeCubeWithHollow(float halfSide, float hollowRadius, int hollowRings, int hollowSegments);

/// A ring torus around +Y (lying flat in the XZ plane), centred on the origin: the circle of
/// `majorRadius` in the XZ plane swept by a tube of `minorRadius` (< majorRadius). `majorSegments`
/// ≥ 3 steps around the axis, `minorSegments` ≥ 3 around the tube; smaller values are raised to
/// these. Both seams are duplicated: (majorSegments + 1) · (minorSegments + 1) vertices and
/// 2 · majorSegments · minorSegments triangles. u = φ / 2π around the axis (φ from +X toward +Z),
/// v = θ / 2π around the tube (θ = 0 on the outer equator, π/2 on top). Normals are the exact
/// unit directions away from the tube's core circle; triangles wind counter-clockwise seen from
/// outside. Its quads are planar trapezoids, so the enclosed volume is exactly
/// 2π²·R·r² · s(majorSegments) · s(minorSegments), s(k) = k·sin(2π/k) / 2π.
[[nodiscard]] Mesh makeTorus(float majorRadius, float minorRadius, int majorSegments, int minorSegments);

/// A floor: the square [−halfSide, halfSide]² in the XZ plane at y = 0, facing +Y, as 2 triangles
/// (counter-clockwise seen from above) with uvs 0..1 across it.
[[nodiscard]] Mesh makePlane(float halfSide);

/// A ship's hull, one unit long from stern (x = −½) to bow (x = ½), 0.28 wide at its widest,
/// from its keel 0.1 below y = 0 (0.06 at the ends) to a flat deck 0.06 above it amidships,
/// rising to 0.09 at the ends. Each of `stations` cross-sections is a U from the deck's port edge
/// round the keel to its starboard edge (`sectionPoints` points); the sections close to a stem
/// line at both ends, and the deck closes the top, so the mesh is closed. The hull's vertices
/// carry smooth normals, the deck's its own, so the edge between them stays sharp.
[[nodiscard]] Mesh makeHull(int stations, int sectionPoints);

/// A mast or a yard: a cylinder of `radius` along +y from 0 to 1, of `segments` sides, capped
/// at both ends (the caps' vertices their own, so the edges stay sharp).
[[nodiscard]] Mesh makeSpar(float radius, int segments);

}  // namespace mane::scenes
