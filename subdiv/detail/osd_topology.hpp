#pragma once
// Private to subdiv/: a validated Cage → OpenSubdiv's Far::TopologyRefiner (Catmull-Clark),
// shared by uniform refinement and the limit surface so both see the same topology and
// boundary rules.

#include <memory>

#include <opensubdiv/far/topologyRefiner.h>

#include "subdiv/cage.hpp"

namespace mane::subdiv::detail {

/// How face-varying UVs are interpolated. Linear along UV boundaries and seams (so both sides
/// of a seam and the texture's borders stay where the artist put them) and smooth elsewhere:
/// OpenSubdiv's FVAR_LINEAR_BOUNDARIES.
inline constexpr auto kUvInterpolation = OpenSubdiv::Sdc::Options::FVAR_LINEAR_BOUNDARIES;

/// Builds the unrefined topology of `cage` (which must pass validateCage), with its creases,
/// corners, boundary rule and, when present, the UVs as face-varying channel 0.
Result<std::unique_ptr<OpenSubdiv::Far::TopologyRefiner>> createTopologyRefiner(const Cage& cage);

}  // namespace mane::subdiv::detail
