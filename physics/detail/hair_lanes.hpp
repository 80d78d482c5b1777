#pragma once
// Internal: the hair step's AVX2 path (hair_step.cpp), a friend of HairSystem so that the
// public header declares nothing of it.

#include <cstddef>
#include <vector>

#include "physics/hair.hpp"

namespace mane::physics::detail {

struct HairLaneKernel {
  /// `simulateBlock`'s `nextBlock` when there is no next block to prefetch.
  static constexpr std::size_t kNoBlock = ~std::size_t{0};

  /// Steps up to detail::kBlockLanes strands from `firstStrand` in lane-by-lane storage
  /// (`scratch`, the calling task's, kept between frames); during the last step's constraint
  /// iterations it prefetches the block at strand `nextBlock` (kNoBlock: none). Same bits as
  /// HairSystem::simulateStrandBlock; without AVX2 it falls back to that.
  static void simulateBlock(HairSystem& self, std::size_t firstStrand, std::size_t lanes, const StepPlan& plan,
                            std::vector<float>& scratch, std::size_t nextBlock);

  /// Asks the memory for part `part` of `parts` of the particles and lane constants of the block
  /// starting at strand `firstStrand`, spread so that the requests overlap the current block's
  /// work instead of queueing up at once.
  static void prefetchBlock(const HairSystem& self, std::size_t firstStrand, int part, int parts) noexcept;
};

}  // namespace mane::physics::detail
