// `jcbb`: joint compatibility branch and bound (Neira & Tardos, IEEE T-RA 2001) adapted to
// verifying one set of putative correspondences. Each correspondence i is one pairing that a
// hypothesis H either contains or not (the interpretation tree has two branches per match), and H
// is kept only while it passes the joint chi-square test; the largest such H wins, ties going to
// the smaller joint Mahalanobis distance, as in the original.
//
// Noise model: both points carry isotropic noise sigma per axis, so a residual q - (R m + t) has
// covariance 2 sigma^2 I.
//
// With a pose prior (T0, P) -- the odometry guess of a loop closure -- the test is the original
// EKF one, linearised at T0 with the left perturbation T = Exp(delta) T0:
//   r_i = q_i - T0 m_i,  J_i = [ -[T0 m_i]x  I ]  (2D: [ perp(T0 m_i)  I ]),
//   D^2(H) = r_H^T (J_H P J_H^T + 2 sigma^2 I)^-1 r_H < chi2(d |H|, alpha).
// Individual compatibility (|H| = 1) gates every match first. D^2 is kept in information form,
//   D^2 = c - b^T A^-1 b,  A = P^-1 + sum J^T J / 2s^2,  b = sum J^T r / 2s^2,  c = sum r^T r /
//   2s^2
// (Woodbury), so adding a pairing is a rank-d update and one p x p solve (p = 3 or 6), never a
// refactorisation of the d|H| x d|H| innovation covariance.
//
// Without a prior the motion is unknown and individual compatibility says nothing; JCBB then
// reduces to: the largest H whose least-squares rigid fit leaves a residual sum e(H) with
//   e(H) / 2 sigma^2 < chi2(d |H| - dof(H), alpha),  dof = 6 in 3D (3 in 2D) for |H| >= d,
// where e(H) comes in closed form from running moments (Umeyama): e = S_m + S_q - 2 sum_i d_i s_i
// over the singular values of the cross-covariance. For |H| = 2 this is exactly a test on the
// pair's length difference, |d_ij| < 2 sigma sqrt(chi2(1, alpha)) -- the correspondence graph
// of Eq. (1) with that eps. Both modes therefore only extend H with matches pairwise compatible
// with all of it (a necessary condition of every pair's own joint test), which is what lets the
// search run at all on hundreds of matches; the bound is JCBB's: |H| + remaining <= best prunes.
#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <numeric>

#include "core/chi2.hpp"
#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "graph/compatibility_graph.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

/// chi2 quantiles by degrees of freedom, computed once each.
class Gates {
 public:
  explicit Gates(double confidence) : p_(confidence) {}
  double operator()(int dof) {
    if (dof >= static_cast<int>(cache_.size()))
      cache_.resize(static_cast<std::size_t>(dof) + 1, -1);
    double& q = cache_[static_cast<std::size_t>(dof)];
    if (q < 0) q = chi2_quantile(p_, dof);
    return q;
  }

 private:
  double p_;
  std::vector<double> cache_;
};

/// Running moments of a hypothesis and its least-squares residual (no prior).
template <int Dim>
struct FitModel {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  int k = 0;
  Vec sum_m = Vec::Zero(), sum_q = Vec::Zero();
  Eigen::Matrix<double, Dim, Dim> sum_mq = Eigen::Matrix<double, Dim, Dim>::Zero();
  double sum_mm = 0.0, sum_qq = 0.0;

  void add(const Vec& m, const Vec& q) {
    ++k;
    sum_m += m;
    sum_q += q;
    sum_mq += m * q.transpose();
    sum_mm += m.squaredNorm();
    sum_qq += q.squaredNorm();
  }
  /// Residual degrees of freedom of |H| = k pairings after fitting SE(Dim).
  int dof() const {
    if (Dim == 3) return k <= 1 ? 0 : k == 2 ? 1 : 3 * k - 6;
    return k <= 1 ? 0 : 2 * k - 3;
  }
  /// min over R, t of sum ||R m + t - q||^2.
  double residual() const {
    const Vec cm = sum_m / k, cq = sum_q / k;
    const Eigen::Matrix<double, Dim, Dim> H = sum_mq - k * cm * cq.transpose();
    const double spread = (sum_mm - k * cm.squaredNorm()) + (sum_qq - k * cq.squaredNorm());
    double best;  // max over rotations of tr(R H)
    if constexpr (Dim == 2) {
      best = std::hypot(H(0, 0) + H(1, 1), H(0, 1) - H(1, 0));
    } else {
      const Eigen::Vector3d s = Eigen::JacobiSVD<Eigen::Matrix3d>(H).singularValues();
      best = s(0) + s(1) + (H.determinant() < 0.0 ? -s(2) : s(2));
    }
    return std::max(0.0, spread - 2.0 * best);
  }
};

/// Information-form joint Mahalanobis distance, linearised at the prior.
template <int Dim>
struct PriorModel {
  static constexpr int P = kPoseDof<Dim>;
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Jac = Eigen::Matrix<double, Dim, P>;
  int k = 0;
  Eigen::Matrix<double, P, P> A;
  Eigen::Matrix<double, P, 1> b = Eigen::Matrix<double, P, 1>::Zero();
  double c = 0.0;

  static Jac jacobian(const Vec& p) {
    Jac J;
    if constexpr (Dim == 2) {
      J << -p(1), 1, 0, p(0), 0, 1;
    } else {
      J.template leftCols<3>() << 0, p(2), -p(1), -p(2), 0, p(0), p(1), -p(0), 0;  // -[p]x
      J.template rightCols<3>().setIdentity();
    }
    return J;
  }
  void add(const Jac& J, const Vec& r, double inv_var) {
    ++k;
    A += inv_var * J.transpose() * J;
    b += inv_var * J.transpose() * r;
    c += inv_var * r.squaredNorm();
  }
  double d2() const { return std::max(0.0, c - b.dot(A.ldlt().solve(b))); }
};

template <int Dim>
class Search {
 public:
  using Vec = Eigen::Matrix<double, Dim, 1>;

  Search(const Correspondences<Dim>& corr, const SolverParams& params, const BitGraph& graph)
      : corr_(corr),
        graph_(graph),
        var2_(2.0 * params.jcbb_point_sigma() * params.jcbb_point_sigma()),
        gates_(params.jcbb.confidence),
        deadline_(deadline_after(params.time_limit_s)) {
    // Without a prior, centred copies: the moments then lose no digits to coordinates far from
    // the origin. With one, the original frames, where the prior and its Jacobians live.
    m_ = corr.source;
    q_ = corr.target;
    if (!corr.prior && corr.size() > 0) {
      m_.colwise() -= Vec(corr.source.rowwise().mean());
      q_.colwise() -= Vec(corr.target.rowwise().mean());
    }
  }

  /// Candidates after individual gating, in search order.
  std::vector<int> candidates() {
    const int n = static_cast<int>(corr_.size());
    std::vector<int> order;
    std::vector<double> key(static_cast<std::size_t>(n));
    if (corr_.prior) {
      const auto& pr = *corr_.prior;
      const double gate = gates_(Dim);
      pred_ = pr.T_target_source * m_;  // T0 m_i, kept for every node's joint test
      for (int i = 0; i < n; ++i) {
        const Vec p = pred_.col(i);
        const auto J = PriorModel<Dim>::jacobian(p);
        const Eigen::Matrix<double, Dim, Dim> S =
            J * pr.covariance * J.transpose() + var2_ * Eigen::Matrix<double, Dim, Dim>::Identity();
        const Vec r = q_.col(i) - p;
        const double d2 = r.dot(S.ldlt().solve(r));
        key[static_cast<std::size_t>(i)] = d2;
        if (d2 < gate) order.push_back(i);
      }
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return key[static_cast<std::size_t>(a)] < key[static_cast<std::size_t>(b)];
      });
    } else {
      order.resize(static_cast<std::size_t>(n));
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(),
                       [&](int a, int b) { return graph_.degree(a) > graph_.degree(b); });
    }
    return order;
  }

  void run(const std::vector<int>& order) {
    std::vector<int> h;
    if (corr_.prior) {
      PriorModel<Dim> model;
      model.A = corr_.prior->covariance.inverse();
      expand(h, model, order);
    } else {
      expand(h, FitModel<Dim>{}, order);
    }
  }

  std::vector<int> best;
  double best_d2 = 0.0;
  long long nodes = 0;
  bool stopped = false;

 private:
  bool test(FitModel<Dim>& model, int i, double& d2) {
    model.add(m_.col(i), q_.col(i));
    const int dof = model.dof();
    d2 = dof == 0 ? 0.0 : model.residual() / var2_;
    return dof == 0 || d2 < gates_(dof);
  }
  bool test(PriorModel<Dim>& model, int i, double& d2) {
    const Vec p = pred_.col(i);
    model.add(PriorModel<Dim>::jacobian(p), q_.col(i) - p, 1.0 / var2_);
    d2 = model.d2();
    return d2 < gates_(Dim * model.k);
  }

  template <class Model>
  void expand(std::vector<int>& h, const Model& model, const std::vector<int>& cand) {
    for (std::size_t k = 0; k < cand.size(); ++k) {
      if (h.size() + (cand.size() - k) <= best.size()) return;  // JCBB's bound
      if ((++nodes & 63) == 0 && SteadyClock::now() >= deadline_) stopped = true;
      if (stopped) return;
      const int c = cand[k];
      Model next = model;
      double d2;
      if (!test(next, c, d2)) continue;
      h.push_back(c);
      if (h.size() > best.size() || (h.size() == best.size() && d2 < best_d2)) {
        best = h;
        best_d2 = d2;
      }
      std::vector<int> sub;
      for (std::size_t j = k + 1; j < cand.size(); ++j) {
        if (graph_.adjacent(c, cand[j])) sub.push_back(cand[j]);
      }
      expand(h, next, sub);
      h.pop_back();
    }
  }

  const Correspondences<Dim>& corr_;
  const BitGraph& graph_;
  const double var2_;
  Gates gates_;
  const SteadyClock::time_point deadline_;
  typename Correspondences<Dim>::Points m_, q_;
  typename Correspondences<Dim>::Points pred_;  ///< prior mode: T0 m_i
};

/// The pair test's graph: Eq. (1) at |d_ij| < 2 sigma sqrt(chi2(1, alpha)).
double pair_eps(const SolverParams& params) {
  return 2.0 * params.jcbb_point_sigma() * std::sqrt(chi2_quantile(params.jcbb.confidence, 1));
}

class JcbbSolver : public SolverBase<JcbbSolver> {
 public:
  bool solves_concurrently() const override { return true; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    Result<Dim> result;
    const auto built = build_graph_stage(corr, params, result, pair_eps(params));
    if (!built) return result;
    const BitGraph& graph = *built;
    SolverParams rest = params;  // the search gets what the graph left of the limit
    rest.time_limit_s = std::max(1e-9, params.time_limit_s - result.times.graph_ms / 1000.0);

    StopWatch search_clock;
    Search<Dim> search(corr, rest, graph);
    search.run(search.candidates());
    result.times.search_ms = search_clock.ms();
    result.counters.branch_nodes = search.nodes;

    StopWatch fit_clock;
    result.inliers = search.best;
    std::sort(result.inliers.begin(), result.inliers.end());
    if (auto T = fit_rigid(corr, result.inliers)) result.T_target_source = *T;
    result.times.fit_ms = fit_clock.ms();
    decide(result, corr, params, !search.stopped);
    return result;
  }

  /// H only grows by matches adjacent to all of it in the pair test's graph: a clique there.
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    return clique_number_bound(corr, params, pair_eps(params), part_size);
  }
};

}  // namespace

void register_jcbb_solver() {
  SolverRegistry::add(
      {"jcbb",
       "JCBB (Neira & Tardos 2001): largest jointly compatible set by chi-square tests, linearised "
       "at the pose prior when the set has one, else on the least-squares fit residual",
       [] { return std::make_unique<JcbbSolver>(); }});
}

const ParamFamily& jcbb_param_family() {
  using K = ParamField::Kind;
  ParamField sigma = bind(&SolverParams::jcbb, &JcbbParams::sigma,
                          {"jcbb-sigma",
                           "jcbb_sigma",
                           "M",
                           "per-axis point noise sigma [m] (0 = inlier threshold / 3)",
                           K::real,
                           0,
                           1e9,
                           "a finite value >= 0 (0 = inlier_threshold / 3)",
                           {},
                           {},
                           {}});
  sigma.report = [](const SolverParams& p) { return p.jcbb_point_sigma(); };
  static const ParamFamily family{"jcbb",
                                  "jcbb",
                                  {sigma, bind(&SolverParams::jcbb, &JcbbParams::confidence,
                                               {"jcbb-confidence",
                                                "jcbb_confidence",
                                                "P",
                                                "level of the chi-square gates",
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
