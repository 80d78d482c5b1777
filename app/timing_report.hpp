#pragma once
// The GPU times of `mane render`'s frames summed up per pass, as a table for people or as
// statistics for its JSON report.

#include <string>
#include <vector>

#include "render/renderer.hpp"

namespace mane::app {

struct PassStatistics {
  std::string pass;
  double medianMs = 0.0;
  double worstMs = 0.0;
};

/// Median and worst GPU time of each pass over all frames, in the order the passes ran, then of
/// "all passes": the span from the first pass's begin to the last one's end (on lavapipe a render
/// pass's draws are rasterized when it ends, and that work can fall between two passes' timers).
[[nodiscard]] std::vector<PassStatistics> passStatistics(const std::vector<std::vector<render::PassTiming>>& frames);

/// The span of "all passes" in one frame, milliseconds (0 for a frame without timings).
[[nodiscard]] double allPassesMilliseconds(const std::vector<render::PassTiming>& frame);

/// "pass  median ms  worst ms", one row per entry, on stdout.
void printTimingTable(const std::vector<PassStatistics>& statistics);

}  // namespace mane::app
