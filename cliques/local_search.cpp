// Dynamic local search for a large clique (DLS-MC, Pullan & Hoos 2006): the lower bound that lets
// an exact search start near omega on graphs whose maximum clique greedy methods miss (brock*).
#include "cliques/detail/local_search.hpp"

#include <algorithm>
#include <limits>

#include "cliques/detail/bbmc.hpp"

namespace verifybench {

using detail::kBits;
using detail::Word;

// The current clique C and, for every vertex outside it, how many members of C it misses:
// 0 = it can be added (N_I(C) in the paper), 1 = it can be swapped in for that one member (N_L(C)).
// Both sets are kept as bitsets, so a pick scans only them.
class CliqueState {
 public:
  explicit CliqueState(const BitGraph& g)
      : g_(g),
        n_(g.size()),
        W_(g.words()),
        miss_(static_cast<std::size_t>(n_), 0),
        pos_(static_cast<std::size_t>(n_), -1),
        sets_(2 * static_cast<std::size_t>(W_), 0) {
    for (int v = 0; v < n_; ++v) set(0, v);  // C is empty: every vertex can be added
  }

  const std::vector<int>& members() const { return members_; }
  bool contains(int v) const { return pos_[static_cast<std::size_t>(v)] >= 0; }
  /// The vertices outside C that miss `misses` (0 or 1) of its members, as a bitset.
  const Word* missing(int misses) const {
    return sets_.data() + static_cast<std::size_t>(misses) * W_;
  }
  long long visits() const { return visits_; }  ///< vertices and words visited by updates

  void add(int v) {  // v misses no member
    pos_[static_cast<std::size_t>(v)] = static_cast<int>(members_.size());
    members_.push_back(v);
    clear(0, v);
    for_each_non_neighbour(v, [&](int x) {
      const int m = miss_[static_cast<std::size_t>(x)]++;
      if (m <= 1) clear(m, x);
      if (m == 0) set(1, x);
    });
  }
  void remove(int v) {
    const int at = pos_[static_cast<std::size_t>(v)];
    const int last = members_.back();
    members_[static_cast<std::size_t>(at)] = last;
    pos_[static_cast<std::size_t>(last)] = at;
    members_.pop_back();
    pos_[static_cast<std::size_t>(v)] = -1;
    for_each_non_neighbour(v, [&](int x) {
      const int m = --miss_[static_cast<std::size_t>(x)];
      if (m == 0) clear(1, x);
      if (m <= 1) set(m, x);
    });
    set(0, v);
  }
  /// The one member of C that v misses (v is in missing(1)).
  int missed_member(int v) const {
    for (int u : members_) {
      if (!g_.adjacent(u, v)) return u;
    }
    return -1;
  }

 private:
  void set(int level, int v) {
    sets_[static_cast<std::size_t>(level) * W_ + static_cast<std::size_t>(v / kBits)] |=
        Word{1} << (v % kBits);
  }
  void clear(int level, int v) {
    sets_[static_cast<std::size_t>(level) * W_ + static_cast<std::size_t>(v / kBits)] &=
        ~(Word{1} << (v % kBits));
  }
  // f(x) for every vertex x != v not adjacent to v (none of them is in C when v joins or leaves).
  template <class F>
  void for_each_non_neighbour(int v, F&& f) {
    const Word* row = g_.row(v);
    visits_ += W_;
    for (int w = 0; w < W_; ++w) {
      Word x = ~row[w];
      if (w == W_ - 1 && n_ % kBits) x &= (Word{1} << (n_ % kBits)) - 1;
      if (w == v / kBits) x &= ~(Word{1} << (v % kBits));
      for (; x; x &= x - 1, ++visits_) f(w * kBits + detail::lowest_bit(x));
    }
  }

  const BitGraph& g_;
  int n_, W_;
  std::vector<int> miss_, pos_;
  std::vector<Word> sets_;  // missing(0), then missing(1)
  std::vector<int> members_;
  long long visits_ = 0;
};

LocalSearch::LocalSearch(const BitGraph& g, const LocalSearchParams& p)
    : g_(g),
      p_(p),
      n_(g.size()),
      rng_(p.seed),
      state_(std::make_unique<CliqueState>(g)),
      penalty_(static_cast<std::size_t>(n_), 0),
      plateau_mark_(static_cast<std::size_t>(n_), -1),
      banned_(static_cast<std::size_t>(n_), -1) {
  if (n_ > 0) {
    last_ = std::uniform_int_distribution<int>(0, n_ - 1)(rng_);
    state_->add(last_);
  }
}

LocalSearch::~LocalSearch() = default;

int LocalSearch::pick(int misses) {
  const Word* candidates = state_->missing(misses);
  int chosen = -1, least = 0, ties = 0;
  picked_ += g_.words();
  detail::for_each_bit(candidates, g_.words(), [&](int v) {
    ++picked_;
    if (banned_[static_cast<std::size_t>(v)] == phase_) return;
    const int pv = penalty_[static_cast<std::size_t>(v)];
    if (chosen < 0 || pv < least) {
      chosen = v;
      least = pv;
      ties = 1;
    } else if (pv == least && std::uniform_int_distribution<int>(0, ties++)(rng_) == 0) {
      chosen = v;
    }
  });
  return chosen;
}

long long LocalSearch::work() const { return picked_ + state_->visits(); }

bool LocalSearch::keep_pace(long long initial, double share, long long search_work, int size,
                            const SteadyClock::time_point& deadline) {
  const long long goal = initial + static_cast<long long>(share * static_cast<double>(search_work));
  return goal > work() && run_until(std::numeric_limits<long long>::max(), goal, deadline) &&
         static_cast<int>(best_.size()) > size;
}

bool LocalSearch::run_until(long long step_goal, long long work_goal,
                            const SteadyClock::time_point& deadline) {
  if (n_ == 0) return false;
  CliqueState& c = *state_;
  const std::size_t before = best_.size();
  auto done = [&] {
    return static_cast<int>(best_.size()) >= p_.target || steps_ >= step_goal ||
           work() >= work_goal || ((steps_ & 255) == 0 && SteadyClock::now() >= deadline);
  };
  while (!done()) {
    // Expansion, then plateau moves while they keep some of the clique the plateau started from
    // and open no addition; back to expansion when one opens (DLS-MC's phases).
    for (;;) {
      // Checked per addition: a first descent into a planted clique of thousands is long.
      for (int v; !done() && (v = pick(0)) >= 0; ++steps_) c.add(last_ = v);
      if (c.members().size() > best_.size()) best_ = c.members();
      if (done()) break;
      ++phase_;
      int kept = 0;
      for (int u : c.members()) {
        plateau_mark_[static_cast<std::size_t>(u)] = phase_;
        ++kept;
      }
      bool opened = false;
      while (kept > 0 && !done()) {
        const int v = pick(1);
        if (v < 0) break;
        const int u = c.missed_member(v);
        c.remove(u);
        banned_[static_cast<std::size_t>(u)] = phase_;
        if (plateau_mark_[static_cast<std::size_t>(u)] == phase_) --kept;
        c.add(last_ = v);
        ++steps_;
        if (pick(0) >= 0) {
          opened = true;
          break;
        }
      }
      if (!opened) break;
    }
    if (done()) break;
    // Penalties: members of a local optimum get one more; every `penalty_delay` cycles every
    // penalty drops by one. Then restart from the last vertex added (or, without penalties, add a
    // random vertex and drop the members it misses).
    for (int u : c.members()) ++penalty_[static_cast<std::size_t>(u)];
    if (++cycles_ % std::max(1, p_.penalty_delay) == 0) {
      for (int& pv : penalty_) pv = std::max(0, pv - 1);
    }
    if (p_.penalty_delay > 1) {
      while (!c.members().empty()) c.remove(c.members().back());
      c.add(last_);
    } else {
      const int v = std::uniform_int_distribution<int>(0, n_ - 1)(rng_);
      if (!c.contains(v)) {
        const std::vector<int> members = c.members();
        for (int u : members) {
          if (!g_.adjacent(u, v)) c.remove(u);
        }
        c.add(last_ = v);
      }
    }
    ++steps_;
  }
  return best_.size() > before;
}

std::vector<int> local_search_clique(const BitGraph& g, const LocalSearchParams& p,
                                     long long* steps_used) {
  LocalSearch search(g, p);
  search.run_until(p.max_steps, std::numeric_limits<long long>::max(),
                   deadline_after(p.time_limit_s));
  if (steps_used) *steps_used = search.steps();
  std::vector<int> best = search.best();
  std::sort(best.begin(), best.end());
  return best;
}

}  // namespace verifybench
