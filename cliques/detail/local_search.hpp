#pragma once
// DLS-MC (Pullan & Hoos 2006) as a resumable search, so that an exact search can interleave it
// (internal to solvers/; local_search_clique in max_clique.hpp is the one-shot form).
#include <memory>
#include <random>
#include <vector>

#include "cliques/max_clique.hpp"
#include "core/timer.hpp"

namespace verifybench {

class CliqueState;

class LocalSearch {
 public:
  LocalSearch(const BitGraph& g, const LocalSearchParams& p);
  ~LocalSearch();
  /// Runs until steps() reaches `step_goal` or work() reaches `work_goal`, the target size is met
  /// or the deadline passes; true when it found a larger clique.
  bool run_until(long long step_goal, long long work_goal, const SteadyClock::time_point& deadline);
  /// An exact search's interleaving (BBMCX's, the decomposition's): runs until work() reaches
  /// `initial` plus `share` of the search's own `search_work`; true when it then holds a clique
  /// larger than `size`.
  bool keep_pace(long long initial, double share, long long search_work, int size,
                 const SteadyClock::time_point& deadline);
  const std::vector<int>& best() const { return best_; }  ///< in the order met, not sorted
  long long steps() const { return steps_; }              ///< additions, swaps and restarts
  /// Vertices scanned and words read so far: what a step costs grows with n and with the share of
  /// non-neighbours, so an interleaving schedule budgets this rather than steps.
  long long work() const;

 private:
  int pick(int misses);  // least-penalty vertex missing `misses` members of C; -1 when none

  const BitGraph& g_;
  LocalSearchParams p_;
  int n_;
  std::mt19937_64 rng_;
  std::unique_ptr<CliqueState> state_;
  std::vector<int> penalty_, plateau_mark_, banned_;
  std::vector<int> best_;
  long long steps_ = 0, picked_ = 0;
  int cycles_ = 0, phase_ = 0, last_ = -1;
};

}  // namespace verifybench
