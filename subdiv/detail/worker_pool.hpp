#pragma once
// Private to subdiv/: threads kept between the parallel loops of forEachRange, and the gate that
// pauses background work (a tessellation being prepared) while a frame's work runs. Waking a
// kept thread costs a fraction of starting one, and a deforming head's frame runs several such
// loops (the cage update, the vertices').

#include <atomic>
#include <cstddef>
#include <cstdint>

namespace mane::subdiv::detail {

/// Whether this thread works in the background (a tessellation being prepared beside the
/// caller's frames): it then gives its core to foreground work (yieldToForeground).
inline thread_local bool inBackground = false;

/// Marks the calling thread as working in the background while it lives.
class BackgroundScope {
public:
  BackgroundScope() { inBackground = true; }
  BackgroundScope(const BackgroundScope&) = delete;
  BackgroundScope& operator=(const BackgroundScope&) = delete;
  ~BackgroundScope() { inBackground = false; }
};

/// Foreground work on more than one thread running now (ForegroundWork, low 16 bits) and
/// threads waiting for background work to end (WaitingForBackground, the bits above).
inline std::atomic<std::uint32_t> backgroundGate{0};
inline constexpr std::uint32_t kForegroundMask = 0xffff;
inline constexpr std::uint32_t kWaiterUnit = 0x10000;

/// On a background thread, waits while foreground work runs and nobody waits for the
/// background; elsewhere returns at once. Background work calls it often, so that a frame's
/// work beside it has every core: on a machine with few cores, a frame's loop on two threads
/// beside a preparing thread otherwise gains nothing over one thread.
inline void yieldToForeground() {
  if (!inBackground) return;
  for (std::uint32_t gate = backgroundGate.load(std::memory_order_acquire);
       (gate & kForegroundMask) != 0 && gate < kWaiterUnit; gate = backgroundGate.load(std::memory_order_acquire))
    backgroundGate.wait(gate, std::memory_order_acquire);
}

/// Foreground work on `threads` threads for as long as it lives: background threads pause
/// meanwhile. Counts nothing on one thread (the background has the other cores then) or on a
/// background thread.
class ForegroundWork {
public:
  explicit ForegroundWork(unsigned threads) : counted_(threads > 1 && !inBackground) {
    if (counted_) backgroundGate.fetch_add(1, std::memory_order_acq_rel);
  }
  ForegroundWork(const ForegroundWork&) = delete;
  ForegroundWork& operator=(const ForegroundWork&) = delete;
  ~ForegroundWork() {
    if (counted_ && (backgroundGate.fetch_sub(1, std::memory_order_acq_rel) & kForegroundMask) == 1)
      backgroundGate.notify_all();
  }

private:
  bool counted_;
};

/// Lets background threads run whatever foreground work runs, for as long as it lives: held
/// while waiting for background work to end, which would otherwise wait for the foreground.
class WaitingForBackground {
public:
  WaitingForBackground() {
    backgroundGate.fetch_add(kWaiterUnit, std::memory_order_acq_rel);
    backgroundGate.notify_all();
  }
  WaitingForBackground(const WaitingForBackground&) = delete;
  WaitingForBackground& operator=(const WaitingForBackground&) = delete;
  ~WaitingForBackground() { backgroundGate.fetch_sub(kWaiterUnit, std::memory_order_acq_rel); }
};

/// Calls task(context, r) once for each range r in [0, ranges), on the calling thread and kept
/// threads, whichever claims r first, and returns true once all have returned. Returns false,
/// having called nothing, when the kept threads are busy with another caller's loop (a loop
/// nested in one, or another thread's) or no thread could be started: the caller then runs the
/// loop itself. Background threads (inBackground) have threads of their own, which work in the
/// background too.
bool runOnKeptThreads(std::size_t ranges, void (*task)(const void* context, std::size_t range), const void* context);

}  // namespace mane::subdiv::detail
