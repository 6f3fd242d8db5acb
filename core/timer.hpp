#pragma once
#include <algorithm>
#include <chrono>

namespace verifybench {

using SteadyClock = std::chrono::steady_clock;

/// Milliseconds since construction (steady clock).
class StopWatch {
 public:
  double ms() const {
    return std::chrono::duration<double, std::milli>(SteadyClock::now() - start_).count();
  }

 private:
  SteadyClock::time_point start_ = SteadyClock::now();
};

/// Now + seconds; an infinite or huge limit becomes a year, a negative one now.
inline SteadyClock::time_point deadline_after(double seconds) {
  constexpr double kYear = 3600.0 * 24 * 365;
  const double s = std::clamp(seconds, 0.0, kYear);  // NaN-free: callers validate
  return SteadyClock::now() +
         std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(s));
}

/// Seconds from now to `deadline` (0 once past it).
inline double seconds_until(SteadyClock::time_point deadline) {
  return std::max(0.0, std::chrono::duration<double>(deadline - SteadyClock::now()).count());
}

}  // namespace verifybench
