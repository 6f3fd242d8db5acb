#include "acceptance/calibration.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

#include "acceptance/prior_gate.hpp"
#include "core/parallel.hpp"
#include "graph/bitgraph.hpp"
#include "core/random.hpp"
#include "core/timer.hpp"

namespace verifybench {

template <int Dim>
TargetGroups target_groups(const Correspondences<Dim>& corr) {
  const auto n = static_cast<int>(corr.size());
  // A hash table on the exact coordinates (open addressing, -0 hashed as +0, which compares
  // equal): O(n), where the sort it replaces took half of a screened calibration at n = 15,000.
  std::size_t mask = 15;
  while (mask < 2 * static_cast<std::size_t>(n)) mask = 2 * mask + 1;
  std::vector<int> slot(mask + 1, -1);  // a group, or -1
  TargetGroups g;
  g.group.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    std::uint64_t h = 0;
    for (int d = 0; d < Dim; ++d) {
      const double x = corr.target(d, i) + 0.0;
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      h = mix_seed(h ^ bits);
    }
    std::size_t s = h & mask;
    while (slot[s] >= 0 && corr.target.col(g.first[static_cast<std::size_t>(slot[s])]) != corr.target.col(i)) {
      s = (s + 1) & mask;
    }
    if (slot[s] < 0) {
      slot[s] = static_cast<int>(g.first.size());
      g.first.push_back(i);
    }
    g.group[static_cast<std::size_t>(i)] = slot[s];
  }
  return g;
}

template <int Dim>
Correspondences<Dim> permute_targets(const Correspondences<Dim>& corr, const TargetGroups& groups,
                                     std::uint64_t seed) {
  const auto n = static_cast<int>(corr.size());
  if (groups.group.size() != static_cast<std::size_t>(n)) {
    throw std::invalid_argument("permute_targets: groups of " +
                                std::to_string(groups.group.size()) + " correspondences for a set of " +
                                std::to_string(n));
  }
  std::vector<int> image(groups.first.size());
  std::iota(image.begin(), image.end(), 0);
  std::mt19937_64 rng(seed);
  std::shuffle(image.begin(), image.end(), rng);
  Correspondences<Dim> out;
  out.source = corr.source;
  out.score = corr.score;
  out.prior = corr.prior;
  out.target.resize(Dim, n);
  for (int i = 0; i < n; ++i) {
    const int g = image[static_cast<std::size_t>(groups.group[static_cast<std::size_t>(i)])];
    out.target.col(i) = corr.target.col(groups.first[static_cast<std::size_t>(g)]);
  }
  return out;
}

template <int Dim>
Correspondences<Dim> permute_targets(const Correspondences<Dim>& corr, std::uint64_t seed) {
  return permute_targets(corr, target_groups(corr), seed);
}

namespace {

/// The null fitted to `scores` (draws, or bounds when screened), and `observed` scored against it.
/// One score is a first draw that reached `observed`: its permutation p, (1 + 1) / (1 + 1) = 1,
/// is all it says (no spread to fit), so p and its range are 1.
void fit_and_score(Calibration& c, const std::vector<int>& scores, int observed, double alpha) {
  c.null = fit_null(scores);
  c.p_value = c.null.p_value(observed);
  const bool one = scores.size() < 2;
  c.p_value_low = one ? c.p_value : optimistic_fit(scores).p_value(observed);
  c.p_value_high = one ? c.p_value : cautious_fit(scores).p_value(observed);
  c.threshold = c.null.threshold(alpha);
}

}  // namespace

template <int Dim>
Calibration calibrate(const Solver& solver, const Correspondences<Dim>& corr,
                      const SolverParams& params, const AcceptParams& accept, int observed,
                      const Deadline& budget, NullDraws* solved) {
  StopWatch clock;
  const int draws = accept.null_draws;
  const double alpha = accept.alpha;
  Calibration c;
  // The grouping of the targets (a sort) is the same for every permuted set; a set itself is
  // rebuilt where it is needed again (an O(n) gather, cheaper than keeping K sets in memory).
  const TargetGroups groups = target_groups(corr);
  auto null_set = [&](int k) {
    return permute_targets(corr, groups, derive_seed(params.seed, {kNullStream, std::uint64_t(k)}));
  };
  // The screen: a bound costs a few small graphs and their core numbers, a null solve a whole
  // search. It is skipped where even bounds of 0 could not accept (the cautious fit's p only grows
  // with them: 34 at alpha = 0.001). Each level (kScreenPartSizes, coarse first) gives up at the
  // first bound that reaches the observed score, at a set the solver offers no bound for, or once
  // even the plain fit of its bounds keeps p >= alpha (more bounds only narrow the cautious fit
  // towards it); then the next, finer level tries.
  const std::vector<int> zeros(static_cast<std::size_t>(kMinDrawsToAccept), 0);
  if (draws > kMinDrawsToAccept && cautious_fit(zeros).p_value(observed) < alpha) {
    const auto n = static_cast<long long>(corr.size());
    long long previous_parts = 0;
    for (const int part_size : kScreenPartSizes) {
      // Every part is non-empty and bounds at least 1: as many parts as the score cannot pass;
      // the same split as the level before gives the same bounds.
      const long long parts = std::max(1LL, (n + part_size - 1) / part_size);
      if (parts == previous_parts || parts >= observed) continue;
      previous_parts = parts;
      std::vector<int> bounds;
      for (int k = 0; k < draws; ++k) {
        const std::optional<int> b = solver.score_bound(null_set(k), params, part_size);
        if (!b || *b >= observed) break;
        bounds.push_back(*b);
        if (static_cast<int>(bounds.size()) < kMinDrawsToAccept) continue;
        if (cautious_fit(bounds).p_value(observed) < alpha) {
          fit_and_score(c, bounds, observed, alpha);
          c.screened = true;
          c.screen_part_size = part_size;
          c.ms = clock.ms();
          return c;
        }
        if (fit_null(bounds).p_value(observed) >= alpha) break;
      }
    }
  }
  // The draws: one after another, each solve using params.threads for its own parallel parts;
  // or, for a solver that may solve several sets at once (Solver::solves_concurrently: not the
  // peers, which fork or run OpenMP), `threads` draws at a time on one thread each (fewer where
  // that many graphs would pass max_graph_bytes). A batch's
  // scores are taken in draw order and the ones past an early stop are dropped, so the result is
  // that of the one-by-one loop for any thread count.
  // At most as many at once as graphs of this size fit in the memory one solve may use.
  const auto fit = static_cast<long long>(params.max_graph_bytes /
                                          std::max<std::size_t>(1, BitGraph::bytes_for(corr.size())));
  const int workers = solver.solves_concurrently()
                          ? static_cast<int>(std::max(1LL, std::min<long long>(
                                {resolve_threads(params.threads), draws, fit})))
                          : 1;
  auto draw_params = [&](int k) {
    SolverParams p = params;
    p.time_limit_s = std::min(params.time_limit_s, budget.limit_s());
    p.seed = derive_seed(derive_seed(params.seed, {kNullStream, std::uint64_t(k)}), {1});
    if (workers > 1) p.threads = 1;
    return p;
  };
  // Past K draws, while the range of p holds alpha, up to `most` in all.
  const int most = std::max(draws, accept.max_null_draws);
  std::vector<int> scores;
  // One draw's outcome: its score (with a limited draw's proven bound), whether the time limit
  // stopped it, and whether the pair's budget cut it short with no bound (it says nothing of
  // chance: dropped, and the draws end there).
  struct Draw {
    int score = 0;
    bool limited = false, cut = false;
    std::optional<std::string> error;  ///< the solve failed (thrown where the draw is taken)
  };
  auto cached = [&](int k) -> std::optional<Draw> {
    if (!solved || k >= static_cast<int>(solved->score.size())) return std::nullopt;
    const int score = solved->score[static_cast<std::size_t>(k)];
    if (score < 0) return std::nullopt;
    Draw d;
    d.score = score;
    d.limited = solved->limited[static_cast<std::size_t>(k)] != 0;
    return d;
  };
  auto solve_draw = [&](int k) {
    const Result<Dim> r = solver.solve(null_set(k), draw_params(k));
    Draw d;
    if (r.status == Status::error) {
      d.error = "null model: permuted set " + std::to_string(k) + " failed: " + r.message;
      return d;
    }
    d.score = static_cast<int>(r.inliers.size());
    d.limited = r.status == Status::time_limit;
    if (d.limited && r.omega_upper_bound) d.score = std::max(d.score, *r.omega_upper_bound);
    d.cut = d.limited && !r.omega_upper_bound && budget.expired();
    return d;
  };
  auto keep = [&](int k, const Draw& d) {
    if (d.error) throw std::runtime_error(*d.error);
    if (!solved || d.cut) return;
    if (static_cast<int>(solved->score.size()) <= k) {
      solved->score.resize(static_cast<std::size_t>(k) + 1, -1);
      solved->limited.resize(static_cast<std::size_t>(k) + 1, 0);
    }
    solved->score[static_cast<std::size_t>(k)] = d.score;
    solved->limited[static_cast<std::size_t>(k)] = d.limited ? 1 : 0;
  };
  // Takes draw k's outcome; true when no further draw can change the decision.
  auto take = [&](int k, const Draw& d) {
    const int score = d.score;
    if (d.limited) ++c.limited_draws;
    scores.push_back(score);
    const int done = k + 1;
    if (done < draws) {
      // Early stops that cannot change the decision of all K draws: a draw that reaches the
      // observed score keeps p >= 2 / (K + 1) (the permutation floor of p_value), so the first
      // one that does decides at once ...
      if (score >= observed && 2.0 / (draws + 1.0) >= alpha) return true;
      // ... and a score beyond every draw, rejected even by a cautious fit of the draws so far.
      return done >= kMinDrawsToAccept && cautious_fit(scores).p_value(observed) < alpha;
    }
    // K draws or more: on only while the range of p holds alpha (a draw that reached the score
    // lifts both ends to the permutation floor, so the range drops out once that is >= alpha).
    if (done >= most) return true;
    return !(optimistic_fit(scores).p_value(observed) < alpha &&
             alpha <= cautious_fit(scores).p_value(observed));
  };
  bool settled = false, out_of_budget = false;
  if (workers <= 1) {
    for (int k = 0; k < most && !settled; ++k) {
      std::optional<Draw> d = cached(k);
      if (!d) {
        if (budget.expired()) break;
        d = solve_draw(k);
        keep(k, *d);
        if (d->cut) break;
      }
      settled = take(k, *d);
    }
  } else {
    WorkerPool pool(workers);
    std::vector<std::optional<Draw>> batch(static_cast<std::size_t>(workers));
    for (int first = 0, count = 0; first < most && !settled && !out_of_budget; first += count) {
      // A batch does not cross the K-th draw, past which most sets are not drawn.
      count = std::min(workers, (first < draws ? draws : most) - first);
      bool all_kept = true;
      for (int j = 0; j < count; ++j) {
        batch[static_cast<std::size_t>(j)] = cached(first + j);
        all_kept = all_kept && batch[static_cast<std::size_t>(j)].has_value();
      }
      if (!all_kept && budget.expired()) {
        // As one by one: the kept draws up to the first unsolved one are taken, then the draws end.
        for (int j = 0; j < count && !settled && batch[static_cast<std::size_t>(j)]; ++j) {
          settled = take(first + j, *batch[static_cast<std::size_t>(j)]);
        }
        break;
      }
      if (!all_kept) {
        pool.parallel_for(count, [&](int j) {
          auto& slot = batch[static_cast<std::size_t>(j)];
          if (!slot) slot = solve_draw(first + j);
        });
      }
      for (int j = 0; j < count && !settled; ++j) {
        const Draw& d = *batch[static_cast<std::size_t>(j)];
        keep(first + j, d);
        if (d.cut) {
          out_of_budget = true;
          break;
        }
        settled = take(first + j, d);
      }
    }
  }
  // Draws stop by themselves (settled) or at the cap; short of both, the budget ran out.
  c.budget_exhausted = !settled && static_cast<int>(scores.size()) < most;
  if (!c.budget_exhausted) {
    fit_and_score(c, scores, observed, alpha);
  } else if (static_cast<int>(scores.size()) >= kMinDrawsToAccept) {
    fit_and_score(c, scores, observed, alpha);
    c.p_value = c.p_value_high;  // what these few draws can vouch for
  } else {
    // Too few draws to say anything: not accepted, p = 1, nothing accepted below the score.
    if (!scores.empty()) c.null = fit_null(scores);
    c.p_value = c.p_value_low = c.p_value_high = 1.0;
    c.threshold = observed + 1;
  }
  c.ms = clock.ms();
  return c;
}

template <int Dim>
void decide_calibrated(Result<Dim>& result, const Correspondences<Dim>& corr,
                       const Calibration& calibration, const AcceptParams& accept) {
  if (accept.rule != AcceptParams::Rule::pvalue || result.status == Status::error) return;
  result.accepted = calibration.p_value < accept.alpha && pins_motion(corr, result.inliers);
  if (result.accepted && accept.prior_gate > 0.0) {
    if (const auto d2 = prior_distance2(corr, result.T_target_source)) {
      result.accepted = inside_prior_gate<Dim>(*d2, accept.prior_gate);
    }
  }
  if (result.status != Status::time_limit) {
    result.status = result.accepted ? Status::ok : Status::rejected;
  }
}

#define VB_INSTANTIATE(D)                                                                  \
  template TargetGroups target_groups<D>(const Correspondences<D>&);                         \
  template Correspondences<D> permute_targets<D>(const Correspondences<D>&, const TargetGroups&, \
                                                 std::uint64_t);                              \
  template Correspondences<D> permute_targets<D>(const Correspondences<D>&, std::uint64_t); \
  template Calibration calibrate<D>(const Solver&, const Correspondences<D>&,               \
                                    const SolverParams&, const AcceptParams&, int,          \
                                    const Deadline&, NullDraws*);                           \
  template void decide_calibrated<D>(Result<D>&, const Correspondences<D>&, const Calibration&, \
                                     const AcceptParams&);
VB_INSTANTIATE(2)
VB_INSTANTIATE(3)
#undef VB_INSTANTIATE

}  // namespace verifybench
