// A request to stop, owned by whoever starts a pass or a study and checked by the pass at every
// step. Each caller has its own token, so stopping one run (the command line's SIGINT handler,
// Python's Ctrl-C, a job runner) leaves every other run in the process alone.
#pragma once

#include <atomic>

namespace rotbeam {

class StopToken {
public:
  /// Asks every pass that watches this token to stop at its next step with an `interrupted`
  /// failure. Async-signal-safe (a lock-free atomic store), so a signal handler may call it.
  void request_stop() noexcept { stop_.store(true, std::memory_order_relaxed); }
  bool stop_requested() const noexcept { return stop_.load(std::memory_order_relaxed); }
  /// Clears the request (before the token is reused for a new run).
  void reset() noexcept { stop_.store(false, std::memory_order_relaxed); }

private:
  std::atomic<bool> stop_{false};
  static_assert(std::atomic<bool>::is_always_lock_free, "the stop flag must be lock-free for signal handlers");
};

}  // namespace rotbeam
