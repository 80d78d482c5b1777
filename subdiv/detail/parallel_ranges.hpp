#pragma once
// Private to subdiv/: runs work over a fixed partition of [0, count) into contiguous ranges,
// one per worker (docs/design.md#determinism). Callers make each item's arithmetic independent
// of the partition and merge per-range outputs in range order, so results do not depend on
// the thread count.

#include <algorithm>
#include <cstddef>
#include <system_error>
#include <thread>
#include <vector>

#include "subdiv/detail/worker_pool.hpp"

namespace mane::subdiv::detail {

/// The workers `threads` asks for over `count` items: at least 1, at most one per
/// `minimumPerWorker` items (handing a range to another thread has a fixed cost to pay back).
[[nodiscard]] inline std::size_t workerCount(std::size_t count, unsigned threads, std::size_t minimumPerWorker) {
  const std::size_t useful = std::max<std::size_t>(1, count / std::max<std::size_t>(1, minimumPerWorker));
  return std::clamp<std::size_t>(threads == 0 ? 1 : threads, 1, useful);
}

/// The first item of range `w` of `workers` over `count` items.
[[nodiscard]] inline std::size_t rangeBegin(std::size_t count, std::size_t workers, std::size_t w) {
  return count * w / workers;
}

/// Calls `work(range, begin, end)` for ranges 0..workers−1 of [0, count), each on one thread,
/// and returns when all are done: on the calling thread and kept threads (runOnKeptThreads),
/// else on threads started for them, else on the calling thread alone. A range's output must
/// depend on its index, never on the thread that runs it.
template <typename Work>
void forEachRange(std::size_t count, std::size_t workers, const Work& work) {
  if (workers <= 1) {
    work(std::size_t(0), std::size_t(0), count);
    return;
  }
  struct Loop {
    const Work* work;
    std::size_t count, workers;
  };
  const Loop loop{&work, count, workers};
  const auto range = [](const void* context, std::size_t w) {
    const Loop& l = *static_cast<const Loop*>(context);
    (*l.work)(w, rangeBegin(l.count, l.workers, w), rangeBegin(l.count, l.workers, w + 1));
  };
  if (runOnKeptThreads(workers, range, &loop)) return;
  std::vector<std::jthread> pool;
  pool.reserve(workers - 1);
  std::size_t inlineFrom = workers;
  for (std::size_t w = 1; w < workers; ++w) {
    try {
      pool.emplace_back([&work, w, b = rangeBegin(count, workers, w), e = rangeBegin(count, workers, w + 1),
                         background = inBackground] {
        inBackground = background;
        work(w, b, e);
      });
    } catch (const std::system_error&) {
      inlineFrom = w;  // no more threads available: the calling thread runs the rest
      break;
    }
  }
  work(std::size_t(0), std::size_t(0), rangeBegin(count, workers, 1));
  for (std::size_t w = inlineFrom; w < workers; ++w)
    work(w, rangeBegin(count, workers, w), rangeBegin(count, workers, w + 1));
  pool.clear();  // joins
}

/// Calls `work(chunk, begin, end)` for chunks 0..chunks−1 of [0, count), worker w of `workers`
/// taking chunks w, w + workers, w + 2·workers, ...: finer than one range per worker, so that
/// work piled up in one part of [0, count) is still shared. Callers merge per-chunk outputs in
/// chunk order, which neither the worker count nor the timing changes.
template <typename Work>
void forEachChunk(std::size_t count, std::size_t chunks, std::size_t workers, const Work& work) {
  forEachRange(workers, workers, [&](std::size_t w, std::size_t, std::size_t) {
    for (std::size_t c = w; c < chunks; c += workers)
      work(c, rangeBegin(count, chunks, c), rangeBegin(count, chunks, c + 1));
  });
}

}  // namespace mane::subdiv::detail
