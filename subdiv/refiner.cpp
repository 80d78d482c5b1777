#include "subdiv/refiner.hpp"

#include <memory>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

namespace mane::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

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

  std::vector<int> vertsPerFace(cage.faceSizes.begin(), cage.faceSizes.end());
  std::vector<int> vertIndices(cage.faceVertices.begin(), cage.faceVertices.end());
  std::vector<int> creasePairs;
  std::vector<float> creaseWeights;
  for (const Crease& crease : cage.creases) {
    creasePairs.push_back(static_cast<int>(crease.a));
    creasePairs.push_back(static_cast<int>(crease.b));
    creaseWeights.push_back(crease.sharpness);
  }
  Far::TopologyDescriptor descriptor;
  descriptor.numVertices = static_cast<int>(cage.positions.size());
  descriptor.numFaces = static_cast<int>(vertsPerFace.size());
  descriptor.numVertsPerFace = vertsPerFace.data();
  descriptor.vertIndicesPerFace = vertIndices.data();
  descriptor.numCreases = static_cast<int>(creaseWeights.size());
  descriptor.creaseVertexIndexPairs = creasePairs.data();
  descriptor.creaseWeights = creaseWeights.data();

  Sdc::Options options;
  options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Factory::Create(descriptor, Factory::Options(Sdc::SCHEME_CATMARK, options)));
  if (!refiner) return fail("OpenSubdiv could not build a topology from the cage");
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
