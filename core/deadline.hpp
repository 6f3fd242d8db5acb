#pragma once
// One time budget: a Deadline is made once, where the user's limit enters (verify(): the pair's
// --time-limit), and handed down; every stage asks it how long is left and whether it passed, so
// the search, the fit and every null solve of the calibrated rule share one budget.
#include <algorithm>
#include <stdexcept>

#include "core/timer.hpp"

namespace verifybench {

/// The one way a stage says the deadline passed before it had a result (the graph's construction,
/// a search's set-up steps): thrown there, caught where the stage's caller records it as
/// Status::time_limit (a solver) or CliqueSearchResult::stopped (a clique search), with the best
/// found so far. Never escapes a solver.
class DeadlinePassed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws DeadlinePassed(what) once `at` has passed.
inline void throw_if_past(SteadyClock::time_point at,
                          const char* what = "the time limit passed") {
  if (SteadyClock::now() >= at) throw DeadlinePassed(what);
}

class Deadline {
 public:
  /// `seconds` from now (an infinite or huge limit is a year away: deadline_after).
  explicit Deadline(double seconds) : at_(deadline_after(seconds)) {}
  static Deadline never() { return Deadline(1e300); }

  bool expired() const { return SteadyClock::now() >= at_; }
  /// Seconds left, 0 once past.
  double seconds_left() const { return seconds_until(at_); }
  /// What a stage started now may take: the time left, never below `floor` (a solver's limit must
  /// be positive; a stage started after expiry stops at its first check).
  double limit_s(double floor = 1e-6) const { return std::max(floor, seconds_left()); }
  SteadyClock::time_point at() const { return at_; }

 private:
  SteadyClock::time_point at_;
};

}  // namespace verifybench
