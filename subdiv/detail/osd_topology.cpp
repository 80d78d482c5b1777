#include "subdiv/detail/osd_topology.hpp"

#include <vector>

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

namespace mane::subdiv::detail {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

Sdc::Options::VtxBoundaryInterpolation toOsd(BoundaryInterpolation boundary) {
  switch (boundary) {
    case BoundaryInterpolation::kNone: return Sdc::Options::VTX_BOUNDARY_NONE;
    case BoundaryInterpolation::kEdgeOnly: return Sdc::Options::VTX_BOUNDARY_EDGE_ONLY;
    case BoundaryInterpolation::kEdgeAndCorner: return Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER;
  }
  return Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER;
}

}  // namespace

Result<std::unique_ptr<Far::TopologyRefiner>> createTopologyRefiner(const Cage& cage) {
  // The descriptor only points at these arrays; the factory copies them into the refiner.
  const std::vector<int> vertsPerFace(cage.faceSizes.begin(), cage.faceSizes.end());
  const std::vector<int> vertIndices(cage.faceVertices.begin(), cage.faceVertices.end());
  const std::vector<int> uvIndices(cage.faceUvIndices.begin(), cage.faceUvIndices.end());
  std::vector<int> creasePairs;
  std::vector<float> creaseWeights;
  for (const Crease& crease : cage.creases) {
    creasePairs.push_back(static_cast<int>(crease.a));
    creasePairs.push_back(static_cast<int>(crease.b));
    creaseWeights.push_back(crease.sharpness);
  }
  std::vector<int> cornerVertices;
  std::vector<float> cornerWeights;
  for (const Corner& corner : cage.corners) {
    cornerVertices.push_back(static_cast<int>(corner.vertex));
    cornerWeights.push_back(corner.sharpness);
  }

  Far::TopologyDescriptor descriptor;
  descriptor.numVertices = static_cast<int>(cage.positions.size());
  descriptor.numFaces = static_cast<int>(vertsPerFace.size());
  descriptor.numVertsPerFace = vertsPerFace.data();
  descriptor.vertIndicesPerFace = vertIndices.data();
  descriptor.numCreases = static_cast<int>(creaseWeights.size());
  descriptor.creaseVertexIndexPairs = creasePairs.data();
  descriptor.creaseWeights = creaseWeights.data();
  descriptor.numCorners = static_cast<int>(cornerWeights.size());
  descriptor.cornerVertexIndices = cornerVertices.data();
  descriptor.cornerWeights = cornerWeights.data();
  Far::TopologyDescriptor::FVarChannel uvChannel;
  if (cage.hasUvs()) {
    uvChannel.numValues = static_cast<int>(cage.uvs.size());
    uvChannel.valueIndices = uvIndices.data();
    descriptor.numFVarChannels = 1;
    descriptor.fvarChannels = &uvChannel;
  }

  Sdc::Options options;
  options.SetVtxBoundaryInterpolation(toOsd(cage.boundary));
  options.SetFVarLinearInterpolation(kUvInterpolation);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Factory::Create(descriptor, Factory::Options(Sdc::SCHEME_CATMARK, options)));
  if (!refiner) return fail("OpenSubdiv could not build a topology from the cage");
  return refiner;
}

}  // namespace mane::subdiv::detail
