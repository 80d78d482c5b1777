#pragma once
// Shapes for the voxel thickness tests, built in code (no assets needed): closed triangle meshes
// and, for the analytic solids they approximate, the exact length of a segment inside them (the
// tests' references). Every mesh is welded (shared vertices by index) and wound counter-clockwise
// seen from outside the material; a hollow's surface is wound the other way. Vertices lie on the
// analytic surface, so each mesh is inscribed in it (the tests bound that sagitta).

#include <cstdint>
#include <vector>

#include <glm/ext/matrix_double3x3.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace mane::render::test {

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

/// The box [lo, hi], 12 triangles.
TriangleMesh box(const glm::vec3& lo, const glm::vec3& hi);
/// A UV sphere: `rings` latitude bands, `segments` longitude steps, one vertex per pole. With
/// `inward` its triangles face the centre (the wall of a hollow).
TriangleMesh sphere(const glm::vec3& centre, float radius, int rings, int segments, bool inward = false);
/// A ring torus about the z axis: tube centre circle of radius `major`, tube radius `minor`.
TriangleMesh torus(float major, float minor, int majorSegments, int minorSegments);
/// An octahedron |x − c| + |y − c| + |z − c| ≤ r (vertices on the axes through c).
TriangleMesh octahedron(const glm::vec3& centre, float radius);
/// `mesh` rotated by `rotation` about the origin, then moved by `offset`.
TriangleMesh transformed(TriangleMesh mesh, const glm::mat3& rotation, const glm::vec3& offset);
/// Both meshes' triangles in one mesh (e.g. a cube and the inward sphere of its hollow).
TriangleMesh combined(TriangleMesh a, const TriangleMesh& b);

// Exact references, all lengths in the shapes' units.

/// Length of segment pq inside the box centre + rotation · [−half, half] (slab clipping).
double boxChord(const glm::dvec3& p, const glm::dvec3& q, const glm::dmat3& rotation, const glm::dvec3& centre,
                const glm::dvec3& half);
/// Depth of `p` below the surface of that box (≥ 0 inside, < 0 outside).
double boxDepth(const glm::dvec3& p, const glm::dmat3& rotation, const glm::dvec3& centre, const glm::dvec3& half);
/// Length of segment pq inside the ball |x − c| ≤ r (the segment–sphere quadratic).
double ballChord(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& c, double r);
/// Length of segment pq inside the torus (√(x² + y²) − major)² + z² ≤ minor²: a march in 4,000
/// steps brackets every sign change of the implicit function, bisection places each to ~1e-15.
double torusInside(const glm::dvec3& p, const glm::dvec3& q, double major, double minor);

}  // namespace mane::render::test
