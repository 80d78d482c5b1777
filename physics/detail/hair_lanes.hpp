#pragma once
// Internal: the hair step's AVX2 path (hair_step.cpp), a friend of HairSystem so that the
// public header declares nothing of it.

#include <cstddef>
#include <vector>

#include "physics/hair.hpp"

namespace mane::physics::detail {

struct HairLaneKernel {
  /// Steps up to detail::kBlockLanes strands from `firstStrand` in lane-by-lane storage (the
  /// system's, kept between steps; `scratch` is the calling task's work space, kept between
  /// frames). Same bits as HairSystem::simulateStrandBlock; without AVX2 it falls back to that.
  /// `intoPrevious`: after a single step whose previous positions are the positions it started
  /// from, write the new positions into the previous positions' array and leave both arrays'
  /// other entries alone (the caller swaps the arrays once every block has run).
  static void simulateBlock(HairSystem& self, std::size_t firstStrand, std::size_t lanes, const StepPlan& plan,
                            HairSystem::LaneFloats& scratch, bool intoPrevious);
};

}  // namespace mane::physics::detail
