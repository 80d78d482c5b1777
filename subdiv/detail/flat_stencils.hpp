#pragma once
// Private to subdiv/: OpenSubdiv's stencil tables (Far::StencilTableReal<double>) copied into
// flat arrays that a deforming cage's update walks in parallel. Each destination point is one
// weighted sum accumulated in registers in the stencil's own order, so the result does not
// depend on how the destinations are split among threads.
//
// The update streams the tables through memory once per frame, so their size is its cost.
// Stencils repeat a few weight lists (a Gregory end cap point's weights depend only on the
// valences around it), so each distinct list is stored once: on the LeePerrySmith cage at
// isolation 1 this leaves the 4-byte source indices as nearly all of the bytes.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <opensubdiv/far/stencilTable.h>

namespace mane::subdiv::detail {

class FlatStencils {
public:
  FlatStencils() = default;
  /// The stencils of `table`, reading points from index 0 of the array `apply` is given and
  /// writing stencil s to index `firstDestination + s`.
  FlatStencils(const OpenSubdiv::Far::StencilTableReal<double>& table, std::size_t firstDestination);

  [[nodiscard]] std::size_t size() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }
  /// Where stencil 0 writes in the array `apply` is given.
  [[nodiscard]] std::size_t firstDestination() const { return firstDestination_; }
  [[nodiscard]] std::size_t weightCount() const { return sources_.size(); }
  /// Weights stored after equal lists were shared.
  [[nodiscard]] std::size_t distinctWeightCount() const { return weights_.size(); }
  /// True when every source lies below the first destination, which `apply` needs.
  [[nodiscard]] bool readsOnlyEarlierPoints() const;
  /// Whether stencil s reads a point whose flag (indexed like `apply`'s array) is set.
  [[nodiscard]] bool readsFlagged(std::size_t s, std::span<const char> flags) const;

  /// points[firstDestination + s] = Σ weight · points[source] for stencils s in [begin, end).
  /// The sources must lie outside every destination of the table (true of OpenSubdiv's refined
  /// and local points, which are computed from earlier points only).
  void apply(std::span<glm::dvec3> points, std::size_t begin, std::size_t end) const;

private:
  std::size_t firstDestination_ = 0;
  std::vector<std::uint32_t> offsets_;        ///< size() + 1 entries into sources_
  std::vector<std::uint32_t> weightOffsets_;  ///< per stencil, where its weight list starts in weights_
  std::vector<std::uint32_t> sources_;
  std::vector<double> weights_;  ///< the distinct weight lists
};

}  // namespace mane::subdiv::detail
