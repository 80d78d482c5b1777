#include "subdiv/refiner.hpp"

#include <memory>

#include <opensubdiv/far/primvarRefiner.h>

#include "subdiv/detail/osd_topology.hpp"

namespace mane::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;

// The vertex type PrimvarRefiner interpolates: it needs Clear and AddWithWeight.
struct Point {
  glm::vec3 position{0.0f};
  void Clear() { position = glm::vec3(0.0f); }
  void AddWithWeight(const Point& source, float weight) { position += weight * source.position; }
};

}  // namespace

Result<RefinedMesh> refineUniformly(const Cage& cage, int level) {
  if (level < 1 || level > 8) return fail("refinement level " + std::to_string(level) + " is outside 1..8");
  if (auto valid = validateCage(cage); !valid) return std::unexpected(valid.error());

  auto created = detail::createTopologyRefiner(cage);
  if (!created) return std::unexpected(created.error());
  const std::unique_ptr<Far::TopologyRefiner> refiner = std::move(*created);
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(level));

  // Vertices of all levels, one after another; PrimvarRefiner fills each level from the last.
  std::vector<Point> points(refiner->GetNumVerticesTotal());
  for (std::size_t v = 0; v < cage.positions.size(); ++v) points[v].position = cage.positions[v];
  const Far::PrimvarRefiner primvars(*refiner);
  Point* source = points.data();
  for (int l = 1; l <= level; ++l) {
    Point* destination = source + refiner->GetLevel(l - 1).GetNumVertices();
    primvars.Interpolate(l, source, destination);
    source = destination;
  }

  const Far::TopologyLevel& last = refiner->GetLevel(level);
  RefinedMesh mesh;
  mesh.positions.reserve(last.GetNumVertices());
  for (int v = 0; v < last.GetNumVertices(); ++v) mesh.positions.push_back(source[v].position);
  mesh.quads.reserve(std::size_t(last.GetNumFaces()) * 4);
  for (int face = 0; face < last.GetNumFaces(); ++face)
    for (int index : last.GetFaceVertices(face)) mesh.quads.push_back(static_cast<std::uint32_t>(index));
  return mesh;
}

}  // namespace mane::subdiv
