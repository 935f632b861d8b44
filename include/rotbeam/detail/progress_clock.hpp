// When a long loop reports its progress: a report is due at most four times a second
// (PassControl::on_progress's contract). The clock is read every `stride` calls, the stride doubled
// (up to 256) while calls come faster than 10 ms apart and halved (down to 1) while they come slower
// than 100 ms apart, so that both microsecond steps and steps of many milliseconds (the elastica at
// 80 modes) report on time. Allocates nothing.
#pragma once

#include <chrono>

namespace rotbeam::detail {

class ProgressClock {
 public:
  ProgressClock() : start_(std::chrono::steady_clock::now()), next_(start_), last_read_(start_) {}
  /// True when a report is due (call once per step).
  bool due() {
    if (++calls_ < stride_) return false;
    calls_ = 0;
    const auto now = std::chrono::steady_clock::now();
    const auto since = now - last_read_;
    last_read_ = now;
    if (since > std::chrono::milliseconds(100) && stride_ > 1) stride_ /= 2;
    else if (since < std::chrono::milliseconds(10) && stride_ < 256) stride_ *= 2;
    if (now < next_) return false;
    next_ = now + std::chrono::milliseconds(250);
    elapsed_s_ = std::chrono::duration<double>(now - start_).count();
    return true;
  }
  /// Wall time from construction to the last due() that returned true [s].
  double elapsed_s() const { return elapsed_s_; }

 private:
  std::chrono::steady_clock::time_point start_, next_, last_read_;
  long calls_ = 0, stride_ = 2;  // the first report comes after a step
  double elapsed_s_ = 0.0;
};

}  // namespace rotbeam::detail
