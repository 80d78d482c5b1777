#include "subdiv/detail/flat_stencils.hpp"

#include <algorithm>
#include <cassert>
#include <string>
#include <unordered_map>
#include <glm/vec3.hpp>

namespace mane::subdiv::detail {

FlatStencils::FlatStencils(const OpenSubdiv::Far::StencilTableReal<double>& table, std::size_t firstDestination)
    : firstDestination_(firstDestination) {
  const int count = table.GetNumStencils();
  offsets_.reserve(static_cast<std::size_t>(count) + 1);
  offsets_.push_back(0);
  weightOffsets_.reserve(static_cast<std::size_t>(count));
  sources_.reserve(table.GetControlIndices().size());
  // Weight lists by their exact bytes: sharing changes no value.
  std::unordered_map<std::string, std::uint32_t> knownLists;
  for (int s = 0; s < count; ++s) {
    const auto stencil = table.GetStencil(OpenSubdiv::Far::Index(s));
    const auto size = static_cast<std::size_t>(stencil.GetSize());
    const OpenSubdiv::Far::Index* indices = stencil.GetVertexIndices();
    const double* weights = stencil.GetWeights();
    for (std::size_t k = 0; k < size; ++k) sources_.push_back(static_cast<std::uint32_t>(indices[k]));
    offsets_.push_back(static_cast<std::uint32_t>(sources_.size()));
    std::string bytes(reinterpret_cast<const char*>(weights), size * sizeof(double));
    const auto [known, added] = knownLists.try_emplace(std::move(bytes), static_cast<std::uint32_t>(weights_.size()));
    if (added) weights_.insert(weights_.end(), weights, weights + size);
    weightOffsets_.push_back(known->second);
  }
}

bool FlatStencils::readsOnlyEarlierPoints() const {
  for (const std::uint32_t source : sources_)
    if (source >= firstDestination_) return false;
  return true;
}

bool FlatStencils::readsFlagged(std::size_t s, std::span<const char> flags) const {
  return std::any_of(sources_.begin() + offsets_[s], sources_.begin() + offsets_[s + 1],
                     [&](std::uint32_t source) { return flags[source] != 0; });
}

namespace {

/// A running weighted sum of points, added to in a fixed order.
struct Sum {
  double x = 0.0, y = 0.0, z = 0.0;
  void add(double w, const glm::dvec3& p) {
    x += w * p.x;
    y += w * p.y;
    z += w * p.z;
  }
};

}  // namespace

void FlatStencils::apply(std::span<glm::dvec3> points, std::size_t begin, std::size_t end) const {
  assert(end <= size() && firstDestination_ + end <= points.size());
  const glm::dvec3* read = points.data();
  glm::dvec3* write = points.data() + firstDestination_;
  const auto sourcesOf = [&](std::size_t s) { return sources_.data() + offsets_[s]; };
  const auto weightsOf = [&](std::size_t s) { return weights_.data() + weightOffsets_[s]; };
  const auto sizeOf = [&](std::size_t s) { return offsets_[s + 1] - offsets_[s]; };
  // Two stencils at a time: each sum is a chain of dependent additions, and two independent
  // chains keep the floating-point units busy (four chains were slower). Each sum still adds its
  // terms in its own order.
  std::size_t s = begin;
  for (; s + 1 < end; s += 2) {
    const std::uint32_t *sourcesA = sourcesOf(s), *sourcesB = sourcesOf(s + 1);
    const double *weightsA = weightsOf(s), *weightsB = weightsOf(s + 1);
    const std::uint32_t sizeA = sizeOf(s), sizeB = sizeOf(s + 1), shared = std::min(sizeA, sizeB);
    Sum a, b;
    for (std::uint32_t k = 0; k < shared; ++k) {
      a.add(weightsA[k], read[sourcesA[k]]);
      b.add(weightsB[k], read[sourcesB[k]]);
    }
    for (std::uint32_t k = shared; k < sizeA; ++k) a.add(weightsA[k], read[sourcesA[k]]);
    for (std::uint32_t k = shared; k < sizeB; ++k) b.add(weightsB[k], read[sourcesB[k]]);
    write[s] = glm::dvec3(a.x, a.y, a.z);
    write[s + 1] = glm::dvec3(b.x, b.y, b.z);
  }
  for (; s < end; ++s) {
    Sum a;
    const std::uint32_t* sources = sourcesOf(s);
    const double* weights = weightsOf(s);
    for (std::uint32_t k = 0, size = sizeOf(s); k < size; ++k) a.add(weights[k], read[sources[k]]);
    write[s] = glm::dvec3(a.x, a.y, a.z);
  }
}

}  // namespace mane::subdiv::detail
