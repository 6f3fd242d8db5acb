#include "harness/progress.hpp"

#include <cmath>

namespace verifybench {

std::string format_duration(double seconds) {
  char buf[64];
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 60) {
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  } else if (seconds < 3600) {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60);
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", m / 60, m % 60);
  }
  return buf;
}

Progress::Progress(std::string label, long long total, bool enabled, std::FILE* out)
    : label_(std::move(label)), total_(total), enabled_(enabled && total > 0), out_(out) {}

void Progress::advance(long long k, const std::string& note) {
  done_ += k;
  if (!enabled_) return;
  const double now = clock_.ms();
  const bool last = done_ >= total_;
  if (!last && now - last_print_ms_ < 1000.0) return;
  last_print_ms_ = now;
  const double elapsed = now / 1000.0;
  const double eta = done_ > 0 ? elapsed * double(total_ - done_) / double(done_) : NAN;
  std::fprintf(out_, "  %s: %lld/%lld, %s elapsed, ETA %s%s%s\n", label_.c_str(), done_, total_,
               format_duration(elapsed).c_str(), last ? "0 s" : format_duration(eta).c_str(),
               note.empty() ? "" : "  ", note.c_str());
  std::fflush(out_);
}

}  // namespace verifybench
