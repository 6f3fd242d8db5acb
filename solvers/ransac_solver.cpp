// The RANSAC family, one engine with switches, registered under the names users know:
//   ransac          the paper's RANSAC-10K: fixed 10,000 hypotheses, inlier-count score
//   ransac-adaptive k = log(1 - p) / log(1 - w^s) (Fischler & Bolles 1981), capped
//   msac            adaptive, truncated quadratic score (Torr & Zisserman 2000)
//   lo-ransac       adaptive + MSAC + local optimisation on each new best (Chum et al. 2003)
//                   + Open3D's edge-length pre-check of each sample
//   prosac          lo-ransac with samples drawn in score order (Chum & Matas 2005)
// Every variant: minimal samples (2 in 2D, 3 in 3D) without replacement, degenerate samples
// rejected, least-squares refit on the final consensus set. Hypothesis t is drawn from its own
// counter-based stream derive_seed(seed, {t}) and hypotheses are reduced in order, so the result is
// the same for any thread count.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#ifdef _OPENMP
#endif

#include "core/parallel.hpp"
#include "core/random.hpp"
#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/consensus.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/detail/ransac_kernels.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

struct Variant {
  bool adaptive = false;
  bool msac = false;
  bool local_optimisation = false;
  double edge_similarity = 0.0;  ///< Open3D's CorrespondenceCheckerBasedOnEdgeLength; 0 = off
  bool prosac = false;
  bool follow_adaptive_flag = false;  ///< `ransac`: adaptive when --ransac-adaptive is given
};

/// Counter-based generator: a SplitMix64 stream from one seed.
struct Stream {
  std::uint64_t state;
  std::uint64_t next() { return mix_seed(state++); }
  /// Uniform in [0, n) by multiply-shift (bias below n / 2^32).
  int below(int n) {
    return static_cast<int>(((next() >> 32) * static_cast<std::uint64_t>(n)) >> 32);
  }
};

/// Samples whose points (nearly) coincide, or in 3D are (nearly) collinear, fix no motion.
template <int Dim>
bool degenerate(const Correspondences<Dim>& corr, const int* s, double min_dist) {
  const double d2 = min_dist * min_dist;
  for (int a = 0; a < Dim; ++a) {
    for (int b = a + 1; b < Dim; ++b) {
      if ((corr.source.col(s[a]) - corr.source.col(s[b])).squaredNorm() < d2) return true;
      if ((corr.target.col(s[a]) - corr.target.col(s[b])).squaredNorm() < d2) return true;
    }
  }
  if constexpr (Dim == 3) {
    const Eigen::Vector3d u = corr.source.col(s[1]) - corr.source.col(s[0]);
    const Eigen::Vector3d v = corr.source.col(s[2]) - corr.source.col(s[0]);
    // Triangle height under min_dist: the sample is close to a line.
    const double longest = std::max({u.norm(), v.norm(), (v - u).norm()});
    if (u.cross(v).norm() < min_dist * longest) return true;
  }
  return false;
}

/// Open3D's edge-length check: every pair's source and target lengths agree within the ratio.
template <int Dim>
bool edges_similar(const Correspondences<Dim>& corr, const int* s, double similarity) {
  for (int a = 0; a < Dim; ++a) {
    for (int b = a + 1; b < Dim; ++b) {
      const double ls = (corr.source.col(s[a]) - corr.source.col(s[b])).norm();
      const double lt = (corr.target.col(s[a]) - corr.target.col(s[b])).norm();
      if (ls < similarity * lt || lt < similarity * ls) return false;
    }
  }
  return true;
}

/// PROSAC's growth schedule (Chum & Matas 2005, Sec. 2.2): hypotheses T'_k after which the
/// sampling pool grows from the k best to k + 1, for a reference budget T_N.
std::vector<long long> prosac_schedule(int n, int m) {
  constexpr double kReferenceBudget = 200000.0;
  std::vector<long long> last(static_cast<std::size_t>(n + 1), 0);
  double T = kReferenceBudget;  // T_m = T_N prod_{i<m} (m - i) / (N - i)
  for (int i = 0; i < m; ++i) T *= double(m - i) / double(n - i);
  long long T_prime = 1;
  last[static_cast<std::size_t>(m)] = T_prime;
  for (int k = m; k < n; ++k) {
    const double next = T * double(k + 1) / double(k + 1 - m);
    T_prime += static_cast<long long>(std::ceil(next - T));
    T = next;
    last[static_cast<std::size_t>(k + 1)] = T_prime;
  }
  return last;
}

template <int Dim>
class Engine {
 public:
  Engine(const Correspondences<Dim>& corr, const SolverParams& params, const Variant& v)
      : corr_(corr),
        params_(params),
        v_(v),
        n_(static_cast<int>(corr.size())),
        pts_(detail::make_scoring_points(corr)),
        thr2_(static_cast<float>(params.inlier_threshold * params.inlier_threshold)) {
    if (v_.prosac && !corr.score.empty()) {
      order_.resize(static_cast<std::size_t>(n_));
      std::iota(order_.begin(), order_.end(), 0);
      std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
        return corr.score[static_cast<std::size_t>(a)] > corr.score[static_cast<std::size_t>(b)];
      });
      if (n_ > Dim) schedule_ = prosac_schedule(n_, Dim);
    }
  }

  Result<Dim> run() {
    Result<Dim> result;
    const auto deadline = deadline_after(params_.time_limit_s);
    WorkerPool workers(params_.threads);  // passive waiting between batches
    const int batch = workers.size() == 1 ? 1 : 256;
    std::vector<Hypothesis> hyps(static_cast<std::size_t>(batch));
    long long needed = params_.ransac.iterations;
    bool finished = true;
    StopWatch search_clock;
    long long t = 0;
    int pool = Dim;  // PROSAC: sampling from the `pool` best
    while (n_ >= Dim && t < needed) {
      if ((batch > 1 || (t & 63) == 0) && SteadyClock::now() >= deadline) {  // every 64 draws
        finished = false;
        break;
      }
      const int count = static_cast<int>(std::min<long long>(batch, needed - t));
      for (int h = 0; h < count; ++h) draw(t + h, pool, hyps[static_cast<std::size_t>(h)]);
      const Score bound = best_score_;
      if (count == 1) {
        evaluate(hyps[0], bound);
      } else {
        workers.parallel_for(count,
                             [&](int h) { evaluate(hyps[static_cast<std::size_t>(h)], bound); });
      }
      for (int h = 0; h < count && t < needed; ++h, ++t) {
        ++result.counters.iterations;
        const Hypothesis& hyp = hyps[static_cast<std::size_t>(h)];
        if (!hyp.valid || !better(hyp.score, best_score_)) {
          // PROSAC: the pool grew, so the best model's pool ratio may now end the search.
          if (v_.adaptive && has_best() && hyp.pool != counted_pool_) {
            needed = adaptive_count(hyp.pool);
          }
          continue;
        }
        best_T_ = hyp.T;
        best_score_ = hyp.score;
        if (v_.local_optimisation) {
          ++result.counters.local_optimisations;
          local_optimisation(t);
        }
        if (v_.adaptive) {
          best_inliers_ = -1;  // a new model: recount
          needed = adaptive_count(hyp.pool);
        }
      }
    }
    result.times.search_ms = search_clock.ms();

    StopWatch fit_clock;
    if (has_best()) {
      take_consensus_with_refit(corr_, best_T_, params_.inlier_threshold, result);
    }
    result.times.fit_ms = fit_clock.ms();
    decide(result, corr_, params_, finished);
    return result;
  }

 private:
  /// Inlier count (higher is better) or MSAC cost (negated, so higher is better too).
  using Score = std::int64_t;
  static constexpr Score kNone = std::numeric_limits<Score>::min();

  struct Hypothesis {
    int sample[Dim];
    int pool = Dim;  ///< PROSAC pool the sample came from
    bool valid = false;
    Rigid<Dim> T;
    Score score = kNone;
  };

  bool has_best() const { return best_score_ != kNone; }
  static bool better(Score a, Score b) { return a > b; }

  /// Exact score of T, or some value <= bound when T cannot beat `bound`.
  Score score(const Rigid<Dim>& T, Score bound) const {
    const detail::CentredMotion c = detail::centre(pts_, T);
    if (v_.msac) {
      const std::int64_t limit = bound == kNone ? std::numeric_limits<std::int64_t>::max() : -bound;
      return -detail::msac_cost(pts_, c, thr2_, limit);
    }
    const int limit = bound == kNone ? -1 : static_cast<int>(bound);
    return detail::count_inliers(pts_, c, thr2_, limit);
  }

  int inlier_count(const Rigid<Dim>& T) const {
    return detail::count_inliers(pts_, detail::centre(pts_, T), thr2_, -1);
  }

  void draw(long long t, int& pool, Hypothesis& hyp) const {
    Stream rng{derive_seed(params_.seed, {static_cast<std::uint64_t>(t)})};
    int* s = hyp.sample;
    if (!schedule_.empty()) {
      // Phase k of PROSAC: the k-th best match plus Dim - 1 drawn from the k - 1 before it.
      while (pool < n_ && t + 1 > schedule_[static_cast<std::size_t>(pool)]) ++pool;
      hyp.pool = pool;
      const bool growing = t + 1 <= schedule_[static_cast<std::size_t>(pool)];
      int drawn = 0;
      if (growing) s[drawn++] = order_[static_cast<std::size_t>(pool - 1)];
      const int from = growing ? pool - 1 : pool;
      while (drawn < Dim) {
        const int c = order_[static_cast<std::size_t>(rng.below(from))];
        if (std::find(s, s + drawn, c) == s + drawn) s[drawn++] = c;
      }
      return;
    }
    for (int drawn = 0; drawn < Dim;) {  // without replacement: redraw repeats
      const int c = rng.below(n_);
      if (std::find(s, s + drawn, c) == s + drawn) s[drawn++] = c;
    }
  }

  void evaluate(Hypothesis& hyp, Score bound) const {
    hyp.valid = false;
    if (degenerate(corr_, hyp.sample, params_.inlier_threshold)) return;
    if (v_.edge_similarity > 0.0 && !edges_similar(corr_, hyp.sample, v_.edge_similarity)) return;
    Eigen::Matrix<double, Dim, Dim> m, q;
    for (int k = 0; k < Dim; ++k) {
      m.col(k) = corr_.source.col(hyp.sample[k]);
      q.col(k) = corr_.target.col(hyp.sample[k]);
    }
    const auto T = fit_rigid_minimal<Dim>(m, q);
    if (!T) return;
    hyp.valid = true;
    hyp.T = *T;
    hyp.score = score(*T, bound);
  }

  /// Least-squares refits on the consensus set while they improve the score (at most 4).
  void iterate_least_squares(Rigid<Dim>& T, Score& s) const {
    for (int round = 0; round < 4; ++round) {
      const auto refit = fit_rigid(corr_, consensus_set(corr_, T, params_.inlier_threshold));
      if (!refit) return;
      const Score rs = score(*refit, s);
      if (!better(rs, s)) return;
      T = *refit;
      s = rs;
    }
  }

  /// LO-RANSAC's inner step on a new best: iterated least squares, then 10 inner samples of
  /// min(|I| / 2, 12) consensus points, each refined the same way; keeps the best.
  void local_optimisation(long long t) {
    iterate_least_squares(best_T_, best_score_);
    const std::vector<int> inliers = consensus_set(corr_, best_T_, params_.inlier_threshold);
    const int size = std::min(static_cast<int>(inliers.size()) / 2, 12);
    if (size <= Dim) return;
    Stream rng{derive_seed(params_.seed, {static_cast<std::uint64_t>(t), 0x4c4fu})};
    std::vector<int> pool = inliers, sample;
    for (int rep = 0; rep < 10; ++rep) {
      for (int k = 0; k < size; ++k) {  // partial Fisher-Yates
        const int j = k + rng.below(static_cast<int>(pool.size()) - k);
        std::swap(pool[static_cast<std::size_t>(k)], pool[static_cast<std::size_t>(j)]);
      }
      sample.assign(pool.begin(), pool.begin() + size);
      auto T = fit_rigid(corr_, sample);
      if (!T) continue;
      Score s = score(*T, kNone);
      iterate_least_squares(*T, s);
      if (better(s, best_score_)) {
        best_T_ = *T;
        best_score_ = s;
      }
    }
  }

  /// k = log(1 - p) / log(1 - w^s) with w the best model's inlier ratio, capped at
  /// ransac_iterations. PROSAC draws from its pool, so there w is the ratio within the pool when
  /// that is higher -- but only once the pool consensus reaches the accept threshold (our stand-in
  /// for Chum & Matas's non-randomness test): a tiny pool is explained by any wrong model.
  long long adaptive_count(int pool) {
    counted_pool_ = pool;
    if (best_inliers_ < 0) {  // once per model: its inlier count and, for PROSAC, their ranks
      best_inliers_ = inlier_count(best_T_);
      best_ranks_.clear();
      if (!schedule_.empty()) {
        for (int i : consensus_set(corr_, best_T_, params_.inlier_threshold)) {
          best_ranks_.push_back(rank_of(i));
        }
        std::sort(best_ranks_.begin(), best_ranks_.end());
      }
    }
    double w = double(best_inliers_) / n_;
    if (!schedule_.empty()) {
      const auto in_pool = static_cast<int>(
          std::lower_bound(best_ranks_.begin(), best_ranks_.end(), pool) - best_ranks_.begin());
      if (in_pool >= params_.accept_threshold(Dim)) w = std::max(w, double(in_pool) / pool);
    }
    const double miss = 1.0 - std::pow(std::min(w, 1.0), Dim);
    const long long cap = params_.ransac.iterations;
    if (miss >= 1.0) return cap;  // w^s below double resolution: no evidence yet
    if (miss <= 0.0) return 0;
    const double k = std::log(1.0 - params_.ransac.confidence) / std::log(miss);
    return k >= double(cap) ? cap : static_cast<long long>(std::ceil(k));
  }

  int rank_of(int i) const {
    if (rank_.empty()) {
      rank_.resize(order_.size());
      for (std::size_t r = 0; r < order_.size(); ++r) {
        rank_[static_cast<std::size_t>(order_[r])] = static_cast<int>(r);
      }
    }
    return rank_[static_cast<std::size_t>(i)];
  }

  const Correspondences<Dim>& corr_;
  const SolverParams& params_;
  const Variant v_;
  const int n_;
  const detail::ScoringPoints pts_;
  const float thr2_;
  std::vector<int> order_;           ///< PROSAC: indices by descending score
  std::vector<long long> schedule_;  ///< PROSAC: T'_k
  mutable std::vector<int> rank_;    ///< PROSAC: position of each index in order_
  Rigid<Dim> best_T_ = Rigid<Dim>::Identity();
  Score best_score_ = kNone;
  int best_inliers_ = -1;        ///< inlier count of best_T_; -1 = not counted yet
  std::vector<int> best_ranks_;  ///< PROSAC: score ranks of best_T_'s consensus, ascending
  int counted_pool_ = -1;        ///< pool size of the last adaptive count
};

/// The largest parts the edge-checking variants bound by (RansacSolver::bound).
constexpr int kEdgeCheckBoundPart = 16;

class RansacSolver : public SolverBase<RansacSolver> {
 public:
  explicit RansacSolver(Variant v) : v_(v) {}
  bool solves_concurrently() const override { return true; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    Variant v = v_;
    if (v.follow_adaptive_flag) v.adaptive = params.ransac.adaptive;
    return Engine<Dim>(corr, params, v).run();
  }

  /// Every variant reports the consensus of one motion (take_consensus_with_refit), so the
  /// consensus bound holds for all; it is offered only where it is cheaper than a null solve. A
  /// bound costs about n min(n, part_size) / 2 pair tests. A null set has no consensus to end
  /// an adaptive count, so a null solve runs the whole cap of `iterations` hypotheses, each
  /// counted over the n correspondences: offered where min(n, part_size) <= iterations (a pair
  /// test costs about a residual: the whole graph's bound broke even near n = 0.6 iterations,
  /// BENCHMARK.md section 21). Where the edge-length pre-check rejects most samples first
  /// (lo-ransac, prosac) a null solve costs 0.5-4 ms, and only parts of up to
  /// kEdgeCheckBoundPart are clearly cheaper: a third to a twenty-fifth of a null solve,
  /// where parts of 64 cost up to nine tenths of one (section 24).
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    const auto part = std::min<Eigen::Index>(corr.size(), part_size);
    if (part > (v_.edge_similarity > 0.0 ? kEdgeCheckBoundPart : params.ransac.iterations)) {
      return std::nullopt;
    }
    return consensus_bound(corr, params, part_size);
  }

 private:
  Variant v_;
};

void add(const char* name, const char* description, Variant v) {
  SolverRegistry::add({name, description, [v] { return std::make_unique<RansacSolver>(v); }});
}

Variant variant(void (*set)(Variant&)) {
  Variant v;
  set(v);
  return v;
}

}  // namespace

void register_ransac_solver() {
  add("ransac",
      "RANSAC: minimal samples (2 in 2D, 3 in 3D) without replacement, fixed 10,000 iterations "
      "(the paper's RANSAC-10K; --ransac-adaptive for the adaptive count), inlier count, seeded",
      variant([](Variant& v) { v.follow_adaptive_flag = true; }));
  add("ransac-adaptive",
      "RANSAC with the adaptive count k = log(1-p)/log(1-w^s), capped at --ransac-iterations",
      variant([](Variant& v) { v.adaptive = true; }));
  add("msac", "MSAC: adaptive RANSAC scored by the truncated quadratic sum min(r^2, t^2)",
      variant([](Variant& v) { v.adaptive = v.msac = true; }));
  const auto lo = [](Variant& v) {
    v.adaptive = v.msac = v.local_optimisation = true;
    v.edge_similarity = 0.9;
  };
  add("lo-ransac",
      "LO-RANSAC: adaptive MSAC, local optimisation (iterated least squares + 10 inner samples) "
      "on each new best, Open3D's 0.9 edge-length pre-check of each sample",
      variant(lo));
  add("prosac",
      "PROSAC: lo-ransac with samples drawn in descending match score (uniform when the set "
      "carries no scores)",
      variant([](Variant& v) {
        v.adaptive = v.msac = v.local_optimisation = v.prosac = true;
        v.edge_similarity = 0.9;
      }));
}

const ParamFamily& ransac_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "ransac",
      "RANSAC family (ransac, ransac-adaptive, msac, lo-ransac, prosac, pcl-*, open3d-*)",
      {bind(&SolverParams::ransac, &RansacParams::iterations,
            {"ransac-iterations",
             "ransac_iterations",
             "K",
             "fixed iteration count, or the cap of the adaptive count",
             K::integer,
             1,
             2e9,
             "an integer >= 1",
             {},
             {},
             {}}),
       bind(&SolverParams::ransac, &RansacParams::adaptive,
            {"ransac-adaptive",
             "ransac_adaptive",
             "",
             "`ransac`: adaptive count k = log(1-p)/log(1-w^s)",
             K::flag,
             0,
             1,
             "",
             {},
             {},
             {}}),
       bind(&SolverParams::ransac, &RansacParams::confidence,
            {"ransac-confidence",
             "ransac_confidence",
             "P",
             "p of the adaptive count",
             K::real,
             1e-9,
             1 - 1e-12,
             "a value in (0, 1)",
             {},
             {},
             {}})}};
  return family;
}

}  // namespace verifybench
