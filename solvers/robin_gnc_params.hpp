#pragma once
// `robin-gnc`'s settings: a plain struct; its rows (CLI option, range, help, Python keyword) are
// declared in robin_gnc_solver.cpp.

namespace verifybench {

/// `robin-gnc` (KISS-Matcher, Lim et al., ICRA 2025): the ROBIN pruning mode; the GNC stage takes
/// the gnc-* settings, the graph --eps and the solver bound --inlier-threshold.
struct RobinParams {
  static constexpr int kMaxCore = 0, kMaxClique = 1;
  int mode = kMaxCore;  ///< 0 = max k-core (KISS-Matcher's robin_mode "max_core"), 1 = max clique
};

}  // namespace verifybench
