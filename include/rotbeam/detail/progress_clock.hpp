// When a long loop reports its progress: the clock is read every 256 calls, a report is due at most
// four times a second (PassControl::on_progress's contract). Allocates nothing.
#pragma once

#include <chrono>

namespace rotbeam::detail {

class ProgressClock {
 public:
  ProgressClock() : start_(std::chrono::steady_clock::now()), next_(start_) {}
  /// True when a report is due (call once per step).
  bool due() {
    if ((++calls_ & 255) != 0) return false;
    const auto now = std::chrono::steady_clock::now();
    if (now < next_) return false;
    next_ = now + std::chrono::milliseconds(250);
    elapsed_s_ = std::chrono::duration<double>(now - start_).count();
    return true;
  }
  /// Wall time from construction to the last due() that returned true [s].
  double elapsed_s() const { return elapsed_s_; }

 private:
  std::chrono::steady_clock::time_point start_, next_;
  long calls_ = 0;
  double elapsed_s_ = 0.0;
};

}  // namespace rotbeam::detail
