#pragma once
// Private to subdiv/: threads kept between the parallel loops of forEachRange. A kept thread
// is woken in 10–40 µs on this project's 2-core VM, where starting one costs 100–200 µs, and a
// deforming head's frame runs several such loops (the cage update, the vertices' evaluation).

#include <cstddef>

namespace mane::subdiv::detail {

/// Calls task(context, r) once for each range r in [0, ranges), on the calling thread and kept
/// threads, whichever claims r first, and returns true once all have returned. Returns false,
/// having called nothing, when the kept threads are busy with another caller's loop (a loop
/// nested in one, or another thread's) or no thread could be started: the caller then runs the
/// loop itself.
bool runOnKeptThreads(std::size_t ranges, void (*task)(const void* context, std::size_t range), const void* context);

}  // namespace mane::subdiv::detail
