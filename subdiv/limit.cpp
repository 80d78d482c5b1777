#include "subdiv/limit.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include "subdiv/detail/flat_stencils.hpp"
#include "subdiv/detail/osd_topology.hpp"
#include "subdiv/detail/parallel_ranges.hpp"
#include "subdiv/detail/patch_sums.hpp"

namespace mane::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;

struct Point2 {
  glm::dvec2 p{0.0};
  void Clear(void* = nullptr) { p = glm::dvec2(0.0); }
  void AddWithWeight(const Point2& source, double weight) { p += weight * source.p; }
};

using detail::kMaxPatchPoints;

// Below this many stencils per worker a thread costs more than it saves.
constexpr std::size_t kMinStencilsPerWorker = 16384;

/// What refining a cage fixes once, whatever its positions: topology, patches, stencils, UVs
/// (positions never move them) and the faces' supports. Shared by a surface and its snapshots.
struct RefinedTopology {
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::unique_ptr<const Far::PatchTable> patches;
  std::unique_ptr<const Far::PatchMap> patchMap;
  std::unique_ptr<const Far::PtexIndices> ptexIndices;
  /// Refined vertices of levels 1..max from cage vertices (factorised), empty without levels.
  detail::FlatStencils refinedStencils;
  /// Local (end cap) points from cage and refined vertices.
  detail::FlatStencils localStencils;
  std::vector<Point2> uvs;  ///< face-varying values of all levels, then local points
  std::vector<PtexFace> ptexFaces;
  std::vector<std::uint32_t> firstPtex;
  /// Per cage face, the cage vertices its limit surface depends on: those of every face that
  /// shares a vertex with it (Catmull-Clark's rules reach no further), as offsets into
  /// supportVertices (one more than there are faces).
  std::vector<std::uint32_t> supportOffsets, supportVertices;

  void buildSupports(const Cage& cage) {
    const std::size_t faceCount = cage.faceSizes.size();
    std::vector<std::uint32_t> faceOffsets(faceCount + 1, 0);
    for (std::size_t f = 0; f < faceCount; ++f) faceOffsets[f + 1] = faceOffsets[f] + cage.faceSizes[f];
    std::vector<std::vector<std::uint32_t>> facesOfVertex(cage.positions.size());
    for (std::size_t f = 0; f < faceCount; ++f)
      for (std::uint32_t k = faceOffsets[f]; k < faceOffsets[f + 1]; ++k)
        facesOfVertex[cage.faceVertices[k]].push_back(std::uint32_t(f));
    supportOffsets.assign(1, 0);
    supportVertices.clear();
    std::vector<std::uint32_t> support;
    for (std::size_t f = 0; f < faceCount; ++f) {
      support.clear();
      for (std::uint32_t k = faceOffsets[f]; k < faceOffsets[f + 1]; ++k)
        for (std::uint32_t neighbour : facesOfVertex[cage.faceVertices[k]])
          support.insert(support.end(), cage.faceVertices.begin() + faceOffsets[neighbour],
                         cage.faceVertices.begin() + faceOffsets[neighbour + 1]);
      std::sort(support.begin(), support.end());
      support.erase(std::unique(support.begin(), support.end()), support.end());
      supportVertices.insert(supportVertices.end(), support.begin(), support.end());
      supportOffsets.push_back(std::uint32_t(supportVertices.size()));
    }
  }

  std::size_t refinedEnd() const { return static_cast<std::size_t>(refiner->GetNumVerticesTotal()); }

  void computeUvs(const Cage& cage) {
    uvs.assign(static_cast<std::size_t>(refiner->GetNumFVarValuesTotal(0)) +
                   static_cast<std::size_t>(patches->GetNumLocalPointsFaceVarying(0)),
               Point2{});
    for (std::size_t t = 0; t < cage.uvs.size(); ++t) uvs[t].p = glm::dvec2(cage.uvs[t]);
    const Far::PrimvarRefinerReal<double> primvars(*refiner);
    Point2* source = uvs.data();
    for (int level = 1; level <= refiner->GetMaxLevel(); ++level) {
      Point2* destination = source + refiner->GetLevel(level - 1).GetNumFVarValues(0);
      primvars.InterpolateFaceVarying(level, source, destination, 0);
      source = destination;
    }
    if (const auto* local = patches->GetLocalPointFaceVaryingStencilTable<double>(0))
      local->UpdateValues(uvs.data(), uvs.data() + refiner->GetNumFVarValuesTotal(0));
  }
};

}  // namespace

/// A surface's state: the shared topology and what moving the cage changes. Copying it makes a
/// snapshot.
struct LimitSurface::Impl {
  std::shared_ptr<const RefinedTopology> topology;
  Cage cage;
  /// Cage, refined levels, local points: what patches index. Control points are kept in
  /// double: second derivatives of deep patches are differences of nearly equal points divided
  /// by the square of a small spacing, and float loses the curvature there.
  std::vector<glm::dvec3> points;
  std::uint64_t revision = 0;
  std::vector<std::uint64_t> ptexRevisions;  ///< per ptex face, the revision of its last change

  /// Stencils [first, first + count) of a table, after `before` stale ones of the same table.
  struct StaleRun {
    std::uint32_t first, count, before;
  };
  /// The stencils that read, directly or through another point, a cage vertex `staleFor` marks
  /// as moved, as runs per table (refined, local). Finding them reads every stencil's sources
  /// once, about what applying them all costs, so they are kept while the same vertices move,
  /// as an animation's do frame after frame (the head's jaw poses, bench/subdiv_bench.cpp).
  std::vector<char> staleFor;
  std::array<std::vector<StaleRun>, 2> staleRuns;

  void findStaleRuns(const std::vector<char>& moved) {
    std::vector<char> stale(points.size(), 0);
    std::copy(moved.begin(), moved.end(), stale.begin());
    for (std::size_t t = 0; t < 2; ++t) {
      const detail::FlatStencils& stencils = *tables()[t];
      std::vector<StaleRun>& runs = staleRuns[t];
      runs.clear();
      std::uint32_t total = 0;
      for (std::uint32_t s = 0; s < stencils.size(); ++s) {
        if (!stencils.readsFlagged(s, stale)) continue;
        stale[stencils.firstDestination() + s] = 1;
        if (!runs.empty() && runs.back().first + runs.back().count == s)
          ++runs.back().count;
        else
          runs.push_back({s, 1, total});
        ++total;
      }
    }
    staleFor = moved;
  }

  std::array<const detail::FlatStencils*, 2> tables() const {
    return {&topology->refinedStencils, &topology->localStencils};
  }

  void copyCagePoints() {
    std::transform(cage.positions.begin(), cage.positions.end(), points.begin(),
                   [](const glm::vec3& p) { return glm::dvec3(p); });
  }

  /// Every point from the cage.
  void computePoints() {
    copyCagePoints();
    for (const detail::FlatStencils* stencils : tables()) stencils->apply(points, 0, stencils->size());
  }

  /// After the cage vertices `moved` marks moved: only the points that read one change; the
  /// others keep their values, which is what computing them again would give. Refined points
  /// read cage points only and local points read cage and refined points, so each stage's
  /// destinations split freely among threads.
  void recomputeMovedPoints(unsigned threads, const std::vector<char>& moved) {
    copyCagePoints();
    if (moved != staleFor) findStaleRuns(moved);
    for (std::size_t t = 0; t < 2; ++t) {
      const detail::FlatStencils& stencils = *tables()[t];
      const std::vector<StaleRun>& runs = staleRuns[t];
      if (runs.empty()) continue;
      const std::size_t stale = runs.back().before + runs.back().count;
      const std::size_t workers = detail::workerCount(stale, threads, kMinStencilsPerWorker);
      // Stale stencils [begin, end) in the order of the runs, each clipped to the range.
      detail::forEachRange(stale, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
        auto run = std::upper_bound(runs.begin(), runs.end(), begin,
                                    [](std::size_t at, const StaleRun& r) { return at < r.before; });
        for (--run; run != runs.end() && run->before < end; ++run) {
          const std::size_t from = std::max<std::size_t>(begin, run->before) - run->before;
          const std::size_t to = std::min<std::size_t>(end, run->before + run->count) - run->before;
          stencils.apply(points, run->first + from, run->first + to);
        }
      });
    }
  }

  const Far::PatchTable::PatchHandle& findPatch(std::uint32_t face, double& u, double& v) const {
    assert(face < topology->ptexFaces.size());
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);
    const Far::PatchTable::PatchHandle* handle = topology->patchMap->FindPatch(static_cast<int>(face), u, v);
    assert(handle != nullptr && "every ptex face of a hole-free cage has patches");
    return *handle;
  }

  /// LimitSample without its uv, on a patch `findPatch` found (u, v as it clamped them).
  LimitSample shapeAt(const Far::PatchTable::PatchHandle& handle, double u, double v) const;
  glm::vec2 uvAt(const Far::PatchTable::PatchHandle& handle, double u, double v) const;
};

LimitSurface::LimitSurface(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
LimitSurface::LimitSurface(const LimitSurface& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
LimitSurface& LimitSurface::operator=(const LimitSurface& other) {
  if (impl_)
    *impl_ = *other.impl_;  // the vectors keep their storage
  else
    impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
LimitSurface::LimitSurface(LimitSurface&&) noexcept = default;
LimitSurface& LimitSurface::operator=(LimitSurface&&) noexcept = default;
LimitSurface::~LimitSurface() = default;

Result<LimitSurface> LimitSurface::create(const Cage& cage, const LimitSurfaceSettings& settings) {
  if (settings.maxIsolationLevel < 1 || settings.maxIsolationLevel > 10)
    return fail("the limit surface's isolation level " + std::to_string(settings.maxIsolationLevel) +
                " is outside 1..10");
  if (auto valid = validateCage(cage); !valid) return std::unexpected(valid.error());
  auto created = detail::createTopologyRefiner(cage);
  if (!created) return std::unexpected(created.error());

  auto topology = std::make_shared<RefinedTopology>();
  topology->refiner = std::move(*created);
  Far::TopologyRefiner& refiner = *topology->refiner;

  Far::PatchTableFactory::Options options(static_cast<unsigned>(settings.maxIsolationLevel));
  options.SetEndCapType(settings.endCap == EndCap::kGregory ? Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS
                                                            : Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS);
  options.SetPatchPrecision<double>();
  options.SetFVarPatchPrecision<double>();
  // Infinitely sharp creases and corners become exact (linear-boundary) patches instead of
  // being isolated to the last level.
  options.useInfSharpPatch = true;
  options.generateVaryingTables = false;
  options.generateFVarTables = cage.hasUvs();
  // Smooth face-varying patches that follow kUvInterpolation, not the legacy bilinear ones.
  options.generateFVarLegacyLinearPatches = false;
  // The refiner must isolate what the patch table expects, so its options come from the table's.
  refiner.RefineAdaptive(options.GetRefineAdaptiveOptions());
  topology->patches.reset(Far::PatchTableFactory::Create(refiner, options));
  if (!topology->patches) return fail("OpenSubdiv could not build a patch table for the cage");
  topology->patchMap = std::make_unique<Far::PatchMap>(*topology->patches);
  topology->ptexIndices = std::make_unique<Far::PtexIndices>(refiner);

  if (refiner.GetMaxLevel() > 0) {
    Far::StencilTableFactoryReal<double>::Options stencilOptions;
    stencilOptions.generateIntermediateLevels = true;
    stencilOptions.factorizeIntermediateLevels = true;
    stencilOptions.generateControlVerts = false;
    stencilOptions.generateOffsets = true;
    stencilOptions.maxLevel = static_cast<unsigned>(refiner.GetMaxLevel());
    const std::unique_ptr<const Far::StencilTableReal<double>> refined(
        Far::StencilTableFactoryReal<double>::Create(refiner, stencilOptions));
    if (!refined) return fail("OpenSubdiv could not build the refinement stencils");
    topology->refinedStencils = detail::FlatStencils(*refined, cage.positions.size());
  }
  if (const auto* local = topology->patches->GetLocalPointStencilTable<double>())
    topology->localStencils = detail::FlatStencils(*local, topology->refinedEnd());
  if (!topology->refinedStencils.readsOnlyEarlierPoints() || !topology->localStencils.readsOnlyEarlierPoints())
    return fail("OpenSubdiv's stencils read points they also write; the parallel update cannot run them");
  if (cage.hasUvs()) topology->computeUvs(cage);

  const Far::TopologyLevel& base = refiner.GetLevel(0);
  topology->firstPtex.resize(cage.faceSizes.size());
  for (int face = 0; face < base.GetNumFaces(); ++face) {
    topology->firstPtex[face] = static_cast<std::uint32_t>(topology->ptexIndices->GetFaceId(face));
    const int size = base.GetFaceVertices(face).size();
    if (size == 4)
      topology->ptexFaces.push_back({static_cast<std::uint32_t>(face), -1});
    else
      for (int j = 0; j < size; ++j) topology->ptexFaces.push_back({static_cast<std::uint32_t>(face), j});
  }
  if (topology->ptexFaces.size() != static_cast<std::size_t>(topology->ptexIndices->GetNumFaces()))
    return fail("OpenSubdiv numbers " + std::to_string(topology->ptexIndices->GetNumFaces()) +
                " ptex faces where the cage has " + std::to_string(topology->ptexFaces.size()));
  topology->buildSupports(cage);

  auto impl = std::make_unique<Impl>();
  impl->cage = cage;
  impl->points.resize(topology->refinedEnd() + static_cast<std::size_t>(topology->patches->GetNumLocalPoints()));
  impl->ptexRevisions.assign(topology->ptexFaces.size(), 0);
  impl->topology = std::move(topology);
  impl->computePoints();
  return LimitSurface(std::move(impl));
}

Result<void> LimitSurface::updatePositions(std::span<const glm::vec3> cagePositions, unsigned threads) {
  const detail::ForegroundWork foreground(threads);  // a preparing tessellation waits
  if (cagePositions.size() != impl_->cage.positions.size())
    return fail("the deformed cage has " + std::to_string(cagePositions.size()) + " vertices; the limit surface has " +
                std::to_string(impl_->cage.positions.size()));
  for (std::size_t v = 0; v < cagePositions.size(); ++v) {
    const glm::vec3& p = cagePositions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return fail("deformed cage vertex " + std::to_string(v) + " has a non-finite position");
  }
  Impl& impl = *impl_;
  const RefinedTopology& topology = *impl.topology;
  std::vector<char> moved(cagePositions.size());
  for (std::size_t v = 0; v < cagePositions.size(); ++v) moved[v] = cagePositions[v] != impl.cage.positions[v];
  ++impl.revision;
  for (std::size_t f = 0; f < topology.firstPtex.size(); ++f) {
    const auto begin = topology.supportVertices.begin() + topology.supportOffsets[f];
    const auto end = topology.supportVertices.begin() + topology.supportOffsets[f + 1];
    if (std::none_of(begin, end, [&](std::uint32_t v) { return moved[v] != 0; })) continue;
    const std::size_t next = f + 1 < topology.firstPtex.size() ? topology.firstPtex[f + 1] : topology.ptexFaces.size();
    for (std::size_t p = topology.firstPtex[f]; p < next; ++p) impl.ptexRevisions[p] = impl.revision;
  }
  std::copy(cagePositions.begin(), cagePositions.end(), impl.cage.positions.begin());
  impl.recomputeMovedPoints(threads, moved);
  return {};
}

LimitSample LimitSurface::evaluate(std::uint32_t ptexFace, double u, double v) const {
  const auto& handle = impl_->findPatch(ptexFace, u, v);
  LimitSample sample = impl_->shapeAt(handle, u, v);
  if (hasUvs()) sample.uv = impl_->uvAt(handle, u, v);
  return sample;
}

LimitSample LimitSurface::evaluateShape(std::uint32_t ptexFace, double u, double v) const {
  const auto& handle = impl_->findPatch(ptexFace, u, v);
  return impl_->shapeAt(handle, u, v);
}

LimitSample LimitSurface::Impl::shapeAt(const Far::PatchTable::PatchHandle& handle, double u, double v) const {
  const Far::PatchTable& patches = *topology->patches;
  detail::PatchWeights w;
  patches.EvaluateBasis(handle, u, v, w[0], w[1], w[2], w[3], w[4], w[5]);
  const Far::ConstIndexArray cvs = patches.GetPatchVertices(handle);
  glm::dvec3 sums[6];
  detail::patchSums(w, std::span(&cvs[0], std::size_t(cvs.size())), points, sums);
  // OpenSubdiv (3.5) scales a patch's derivatives by 2^depth, the depth counting from the cage
  // face; a non-quad face's ptex sub-face starts one level down, so its derivatives come out
  // twice what they are per unit of the sub-face's own (u, v) (checked against finite
  // differences in tests/subdiv/limit_test.cpp). Normals and curvature do not depend on the
  // scale; Jacobians (areas) do.
  if (patches.GetPatchParam(handle).NonQuadRoot()) {
    for (int d = 1; d <= 2; ++d) sums[d] *= 0.5;
    for (int d = 3; d <= 5; ++d) sums[d] *= 0.25;
  }
  LimitSample sample;
  sample.position = glm::vec3(sums[0]);
  sample.du = glm::vec3(sums[1]);
  sample.dv = glm::vec3(sums[2]);
  sample.duu = glm::vec3(sums[3]);
  sample.duv = glm::vec3(sums[4]);
  sample.dvv = glm::vec3(sums[5]);
  const glm::dvec3 normal = glm::cross(sums[1], sums[2]);
  const double length = glm::length(normal);
  sample.normal = length > 0.0 ? glm::vec3(normal / length) : glm::vec3(0.0f);
  sample.curvature = curvatureFromDerivatives(sums[1], sums[2], sums[3], sums[4], sums[5]);
  return sample;
}

glm::dvec3 LimitSurface::evaluatePosition(std::uint32_t ptexFace, double u, double v) const {
  const auto& handle = impl_->findPatch(ptexFace, u, v);
  double w[kMaxPatchPoints];
  impl_->topology->patches->EvaluateBasis(handle, u, v, w);
  const Far::ConstIndexArray cvs = impl_->topology->patches->GetPatchVertices(handle);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < cvs.size(); ++i) sum += w[i] * impl_->points[static_cast<std::size_t>(cvs[i])];
  return sum;
}

glm::vec2 LimitSurface::evaluateUv(std::uint32_t ptexFace, double u, double v) const {
  if (!hasUvs()) return glm::vec2(0.0f);
  const auto& handle = impl_->findPatch(ptexFace, u, v);
  return impl_->uvAt(handle, u, v);
}

glm::vec2 LimitSurface::Impl::uvAt(const Far::PatchTable::PatchHandle& handle, double u, double v) const {
  double w[kMaxPatchPoints];
  const Far::PatchTable& patches = *topology->patches;
  patches.EvaluateBasisFaceVarying(handle, u, v, w, nullptr, nullptr, nullptr, nullptr, nullptr, 0);
  const Far::ConstIndexArray values = patches.GetPatchFVarValues(handle, 0);
  glm::dvec2 sum(0.0);
  for (int i = 0; i < values.size(); ++i) sum += w[i] * topology->uvs[static_cast<std::size_t>(values[i])].p;
  return glm::vec2(sum);
}

std::uint64_t LimitSurface::revision() const {
  return impl_->revision;
}

std::uint64_t LimitSurface::changedAt(std::uint32_t ptexFace) const {
  return impl_->ptexRevisions.at(ptexFace);
}

std::uint32_t LimitSurface::ptexFaceCount() const {
  return static_cast<std::uint32_t>(impl_->topology->ptexFaces.size());
}

PtexFace LimitSurface::ptexFace(std::uint32_t ptexFace) const {
  return impl_->topology->ptexFaces.at(ptexFace);
}

std::uint32_t LimitSurface::firstPtexFace(std::uint32_t cageFace) const {
  return impl_->topology->firstPtex.at(cageFace);
}

PtexAdjacency LimitSurface::ptexAdjacency(std::uint32_t ptexFace) const {
  const PtexFace& face = impl_->topology->ptexFaces.at(ptexFace);
  PtexAdjacency adjacency;
  impl_->topology->ptexIndices->GetAdjacency(*impl_->topology->refiner, static_cast<int>(face.cageFace),
                                             std::max(face.subFace, 0), adjacency.faces.data(), adjacency.edges.data());
  return adjacency;
}

const Cage& LimitSurface::cage() const {
  return impl_->cage;
}

bool LimitSurface::hasUvs() const {
  return impl_->cage.hasUvs();
}

std::size_t LimitSurface::patchCount() const {
  return static_cast<std::size_t>(impl_->topology->patches->GetNumPatchesTotal());
}

std::size_t LimitSurface::controlPointCount() const {
  return impl_->points.size();
}

}  // namespace mane::subdiv
