#pragma once
// Progress of a long command on stderr: "label: done/total, elapsed, ETA", at most once a second
// and once at the end, so a sweep, a dump run or a DIMACS batch never sits silent.
#include <cstdio>
#include <string>

#include "core/timer.hpp"

namespace verifybench {

class Progress {
 public:
  /// Prints nothing when `enabled` is false (the CLI's --quiet) or total <= 0.
  Progress(std::string label, long long total, bool enabled, std::FILE* out = stderr);
  /// `k` more units done; `note` (e.g. the point just finished) is appended to the line.
  void advance(long long k = 1, const std::string& note = "");
  long long done() const { return done_; }

 private:
  std::string label_;
  long long total_, done_ = 0;
  bool enabled_;
  std::FILE* out_;
  StopWatch clock_;
  double last_print_ms_ = -1e9;
};

/// "12.3 s", "4 min 05 s", "1 h 02 min".
std::string format_duration(double seconds);

}  // namespace verifybench
