// `sc2-pcr`: SC2-PCR (Chen, Sun, Yang, Tao, "SC2-PCR: A Second Order Spatial Compatibility for
// Efficient and Robust Point Cloud Registration", CVPR 2022), as the authors' code runs it:
//   1. the hard first-order compatibility C at d_thr = eps (Eqs. 4-6): the graph of Eq. (1);
//   2. seeds: the leading eigenvector of the soft first-order measure max(0, 1 - d_ij^2 / d_thr^2)
//      (spectral matching, power iteration) scores each correspondence; those that score highest
//      within nms_radius in the source (non-maximum suppression) are seeds, at most seed_ratio n;
//   3. two-stage consensus sampling around each seed: its k1 best correspondences by SC2 (Eq. 7,
//      detail/sc2.hpp), then the k2 best of those by the SC2 computed within them;
//   4. local spectral matching: the k2 weighted by the leading eigenvector of their soft measure,
//      and a weighted least-squares rigid fit per seed;
//   5. the hypothesis with the most residuals under tau = inlier_threshold wins, and is refined by
//      refits on its inliers weighted 1 / (1 + (r / tau)^2) until the inlier count stops changing.
// The inliers are the final motion's consensus. SC2 is never stored: its seed rows come from the
// bitset graph (n^2 / 8 bytes, refused above max_graph_bytes), the soft measure from the points.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/consensus.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/detail/sc2.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

/// The soft first-order measure of a compatible pair (the authors' SC_measure), 0 otherwise.
template <int Dim>
double soft_measure(const Correspondences<Dim>& corr, int i, int j, double d_thr) {
  const double d = (corr.source.col(i) - corr.source.col(j)).norm() -
                   (corr.target.col(i) - corr.target.col(j)).norm();
  return std::max(0.0, 1.0 - d * d / (d_thr * d_thr));
}

/// Leading eigenvector of the soft measure over all correspondences (M_ii = 1) by power
/// iteration from ones; it is nonzero only on edges of the graph. nullopt past the deadline.
template <int Dim>
std::optional<std::vector<double>> spectral_scores(const Correspondences<Dim>& corr,
                                                   const BitGraph& g, const SolverParams& params,
                                                   SteadyClock::time_point deadline) {
  const int n = g.size();
  std::vector<double> v(static_cast<std::size_t>(n), 1.0), next(v.size());
  for (int it = 0; it < params.sc2.power_iterations; ++it) {
    next = v;  // the diagonal
    for (int i = 0; i < n; ++i) {
      if ((i & 63) == 63 && SteadyClock::now() >= deadline) return std::nullopt;
      const BitGraph::Word* row = g.row(i);
      for (int w = (i + 1) / BitGraph::kWordBits; w < g.words(); ++w) {
        for (BitGraph::Word bits = row[w]; bits; bits &= bits - 1) {
          const int j = w * BitGraph::kWordBits + __builtin_ctzll(bits);
          if (j <= i) continue;
          const double m = soft_measure(corr, i, j, params.eps);
          next[static_cast<std::size_t>(i)] += m * v[static_cast<std::size_t>(j)];
          next[static_cast<std::size_t>(j)] += m * v[static_cast<std::size_t>(i)];
        }
      }
    }
    double norm = 0.0;
    for (double x : next) norm += x * x;
    norm = std::sqrt(norm) + 1e-6;
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = next[i] / norm;
  }
  return v;
}

/// Non-maximum suppression: a correspondence is a seed when no other within nms_radius in the
/// source scores higher; the best at most max(1, floor(seed_ratio n)), highest score first. Past
/// the deadline, those found so far.
template <int Dim>
std::vector<int> pick_seeds(const Correspondences<Dim>& corr, const std::vector<double>& score,
                            const SolverParams& params, SteadyClock::time_point deadline) {
  const int n = static_cast<int>(score.size());
  const double r2 = params.sc2.nms_radius * params.sc2.nms_radius;
  std::vector<int> seeds;
  for (int i = 0; i < n; ++i) {
    if ((i & 63) == 63 && SteadyClock::now() >= deadline) break;
    bool local_max = true;
    for (int j = 0; j < n && local_max; ++j) {
      local_max = !(score[static_cast<std::size_t>(j)] > score[static_cast<std::size_t>(i)] &&
                    (corr.source.col(i) - corr.source.col(j)).squaredNorm() < r2);
    }
    if (local_max) seeds.push_back(i);
  }
  std::stable_sort(seeds.begin(), seeds.end(), [&](int a, int b) {
    return score[static_cast<std::size_t>(a)] > score[static_cast<std::size_t>(b)];
  });
  const auto cap = std::max<std::size_t>(1, static_cast<std::size_t>(params.sc2.seed_ratio * n));
  if (seeds.size() > cap) seeds.resize(cap);
  return seeds;
}

/// The seed, then the k - 1 others of highest value (ties to the lower index).
std::vector<int> best_k(int seed, const std::vector<int>& members, const std::vector<int>& value,
                        int k) {
  std::vector<int> order;
  for (std::size_t m = 0; m < members.size(); ++m) {
    if (members[m] != seed) order.push_back(static_cast<int>(m));
  }
  const auto keep = std::min(order.size(), static_cast<std::size_t>(std::max(k - 1, 0)));
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep), order.end(),
                    [&](int a, int b) {
                      const int va = value[static_cast<std::size_t>(a)];
                      const int vb = value[static_cast<std::size_t>(b)];
                      return va != vb ? va > vb
                                      : members[static_cast<std::size_t>(a)] <
                                            members[static_cast<std::size_t>(b)];
                    });
  std::vector<int> out{seed};
  for (std::size_t m = 0; m < keep; ++m) out.push_back(members[static_cast<std::size_t>(order[m])]);
  return out;
}

/// Steps 3 and 4 for one seed: the motion of its weighted consensus set, nullopt if degenerate.
template <int Dim>
std::optional<Rigid<Dim>> seed_hypothesis(const Correspondences<Dim>& corr, const BitGraph& g,
                                          int seed, const SolverParams& params,
                                          std::vector<int>& row) {
  const int n = g.size();
  const int k1 = std::min(params.sc2.k1, n), k2 = std::min(params.sc2.k2, k1);
  sc2_row(g, seed, row);  // first stage: the k1 best by SC2 (Eq. 7)
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  const std::vector<int> first = best_k(seed, all, row, k1);
  // Second stage: SC2 within the first stage's set, seed row: C_sb sum_c C_sc C_cb.
  const auto c = [&](int a, int b) { return a == b || g.adjacent(a, b); };
  std::vector<int> local(first.size(), 0);
  for (std::size_t b = 0; b < first.size(); ++b) {
    if (!c(seed, first[b])) continue;
    for (int m : first) local[b] += c(seed, m) && c(m, first[b]);
  }
  const std::vector<int> second = best_k(seed, first, local, k2);
  // Local spectral matching: the leading eigenvector of the soft measure (zero diagonal).
  const std::size_t k = second.size();
  Eigen::MatrixXd M =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
  for (std::size_t a = 0; a < k; ++a) {
    for (std::size_t b = a + 1; b < k; ++b) {
      M(a, b) = M(b, a) = soft_measure(corr, second[a], second[b], params.eps);
    }
  }
  Eigen::VectorXd v = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(k));
  for (int it = 0; it < params.sc2.power_iterations; ++it) {
    const Eigen::VectorXd mv = M * v;
    v = mv / (mv.norm() + 1e-6);
  }
  return fit_rigid(corr, second, std::vector<double>(v.data(), v.data() + v.size()));
}

class Sc2PcrSolver : public SolverBase<Sc2PcrSolver> {
 public:
  bool solves_concurrently() const override { return true; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    const auto deadline = deadline_after(params.time_limit_s);
    Result<Dim> result;
    const auto built = build_graph_stage(corr, params, result);
    if (!built) return result;
    const BitGraph& g = *built;

    StopWatch search_clock;
    bool finished = true;
    std::size_t best_count = 0;
    Rigid<Dim> best = Rigid<Dim>::Identity();
    if (const auto score = spectral_scores(corr, g, params, deadline)) {
      std::vector<int> row;
      for (int seed : pick_seeds(corr, *score, params, deadline)) {
        if (SteadyClock::now() >= deadline) {
          finished = false;
          break;
        }
        ++result.counters.iterations;
        const auto T = seed_hypothesis(corr, g, seed, params, row);
        if (!T) continue;
        const std::size_t count = consensus_count(corr, *T, params.inlier_threshold);
        if (count > best_count) best_count = count, best = *T;
      }
    } else {
      finished = false;
    }
    result.times.search_ms = search_clock.ms();

    StopWatch fit_clock;
    if (best_count > 0) refine(corr, best, params, result);
    result.times.fit_ms = fit_clock.ms();
    decide(result, corr, params, finished);
    return result;
  }

  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    return consensus_bound(corr, params, part_size);
  }

 private:
  /// Step 5's refinement (the authors' post_refinement): refit on the inliers, weighted
  /// 1 / (1 + (r / tau)^2), until their count repeats or refine_iterations refits ran.
  template <int Dim>
  static void refine(const Correspondences<Dim>& corr, Rigid<Dim> T, const SolverParams& params,
                     Result<Dim>& result) {
    const double tau = params.inlier_threshold;
    std::size_t previous = 0;
    for (int it = 0; it < params.sc2.refine_iterations; ++it) {
      const std::vector<int> inliers = consensus_set(corr, T, tau);
      if (inliers.size() == previous) break;
      previous = inliers.size();
      std::vector<double> w;
      for (int i : inliers) {
        const double r = (T * corr.source.col(i) - corr.target.col(i)).norm() / tau;
        w.push_back(1.0 / (1.0 + r * r));
      }
      const auto refit = fit_rigid(corr, inliers, w);
      if (!refit) break;
      T = *refit;
    }
    result.T_target_source = T;
    result.inliers = consensus_set(corr, T, tau);
  }
};

}  // namespace

void register_sc2pcr_solver() {
  SolverRegistry::add(
      {"sc2-pcr",
       "SC2-PCR (Chen et al. 2022): second order compatibility C (.) (C C), spectral seeds with "
       "NMS, two-stage consensus sampling, weighted fits, best by inlier count, refined",
       [] { return std::make_unique<Sc2PcrSolver>(); }});
}

const ParamFamily& sc2_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "sc2",
      "sc2-pcr (d_thr = --eps, tau = --inlier-threshold; defaults: the authors' configs)",
      {bind(&SolverParams::sc2, &Sc2Params::seed_ratio,
            {"sc2-seed-ratio",
             "sc2_seed_ratio",
             "R",
             "at most R n correspondences become seeds (authors: 0.2)",
             K::real,
             1e-9,
             1,
             "a value in (0, 1]",
             {},
             {},
             {}}),
       bind(&SolverParams::sc2, &Sc2Params::nms_radius,
            {"sc2-nms-radius",
             "sc2_nms_radius",
             "M",
             "seed non-maximum suppression radius in the source [m] (authors: 0.1)",
             K::real,
             0,
             1e12,
             "a finite value >= 0",
             {},
             {},
             {}}),
       bind(&SolverParams::sc2, &Sc2Params::k1,
            {"sc2-k1",
             "sc2_k1",
             "K",
             "first-stage consensus set size (authors: 30)",
             K::integer,
             2,
             1 << 20,
             "an integer >= 2",
             {},
             {},
             {}}),
       bind(&SolverParams::sc2, &Sc2Params::k2,
            {"sc2-k2",
             "sc2_k2",
             "K",
             "second-stage consensus set size (authors: 20)",
             K::integer,
             2,
             1 << 20,
             "an integer >= 2",
             {},
             {},
             {}}),
       bind(&SolverParams::sc2, &Sc2Params::power_iterations,
            {"sc2-power-iterations",
             "sc2_power_iterations",
             "K",
             "power iterations of the spectral scores (authors: 10)",
             K::integer,
             1,
             1 << 20,
             "an integer >= 1",
             {},
             {},
             {}}),
       bind(&SolverParams::sc2, &Sc2Params::refine_iterations,
            {"sc2-refine-iterations",
             "sc2_refine_iterations",
             "K",
             "reweighted refits of the final motion at most (authors: 20)",
             K::integer,
             0,
             1 << 20,
             "an integer >= 0",
             {},
             {},
             {}})}};
  return family;
}

}  // namespace verifybench
