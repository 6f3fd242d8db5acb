// `clipper`: CLIPPER+ (Fathian, Summers, "CLIPPER+: A Fast Maximal Clique Algorithm for Robust
// Global Registration", RA-L 2024) on the weighted consistency graph of CLIPPER (Lusk, Fathian,
// How, "CLIPPER: A Graph-Theoretic Framework for Robust Data Association", ICRA 2021):
//   1. the consistency graph: Eq. (1) at --eps (CLIPPER's pairwise Euclidean-distance invariant
//      with epsilon = eps), as a bitset graph; each edge scored s = exp(-c^2 / (2 sigma^2)) by the
//      pair's length difference c (binary with --clipper-binary, CLIPPER+'s unweighted graphs);
//   2. core numbers, CLIPPER+'s Algorithm 1 (degeneracy-ordered greedy maximal clique) and its
//      certificate: a clique of max core + 1 vertices is a maximum clique, returned at once;
//   3. pruning: only vertices whose core number reaches the heuristic clique's size can lie in a
//      larger clique; CLIPPER's relaxation, max u^T (M - d C-bar) u on the unit sphere's positive
//      orthant, by projected gradient ascent with the penalty d grown until u's support holds no
//      inconsistent pair, runs on them from u0 = ones off the heuristic clique; the support of u
//      (u_i > 1e-9) is its clique, kept when at least as large as the heuristic one;
//   4. the motion: the least-squares (Arun / Umeyama) fit of the selection, which is reported as
//      the inliers, as the authors' registration example does (Arun's method on the clique, no
//      consensus step).
// --clipper-no-kcore skips 2-3's core stage: plain CLIPPER on the whole graph from a random u0
// (seeded by --seed). The method is dimension-free (pair lengths), so 2D runs the same way. All
// in one thread after the graph (built with --threads), so the result never depends on it.
// Details and sources of each default: solvers/detail/clipper.hpp and the rows below.
#include <algorithm>
#include <cmath>

#include "cliques/max_clique.hpp"
#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/clipper.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

class ClipperSolver : public SolverBase<ClipperSolver> {
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
    const ClipperParams& p = params.clipper;
    ClipperSettings settings;
    settings.kcore = !p.no_kcore;
    settings.seed = params.seed;
    settings.optim.tol_u = p.tol_u;
    settings.optim.tol_f = p.tol_f;
    settings.optim.max_inner = p.max_inner;
    settings.optim.max_outer = p.max_outer;
    settings.optim.max_line_search = p.max_line_search;
    settings.optim.beta = p.beta;
    settings.optim.armijo = p.armijo;
    settings.optim.zero_eps = p.zero_eps;
    settings.optim.deadline = deadline;
    const std::size_t graph_bytes = BitGraph::bytes_for(static_cast<std::size_t>(g.size()));
    settings.max_bytes =
        params.max_graph_bytes > graph_bytes ? params.max_graph_bytes - graph_bytes : 0;
    const double eps = params.eps;
    const double sigma = p.sigma > 0.0 ? p.sigma : 0.5 * eps;
    ClipperWeight weight;
    if (!p.binary) {
      weight = [&corr, eps, sigma](int i, int j) {
        return clipper_score(pair_length_difference(corr, i, j), eps, sigma);
      };
    }
    const ClipperSelection selection = clipper_select(g, settings, weight);
    result.counters.iterations = selection.optim.steps;
    if (selection.max_core >= 0) result.omega_upper_bound = selection.max_core + 1;
    result.inliers = selection.clique;
    result.times.search_ms = search_clock.ms();

    StopWatch fit_clock;
    if (result.inliers.size() >= 2) {
      if (const auto T = fit_rigid(corr, result.inliers)) result.T_target_source = *T;
    }
    result.times.fit_ms = fit_clock.ms();
    decide(result, corr, params, !selection.timed_out);
    return result;
  }

  /// The selection is a clique of the Eq. (1) graph at eps.
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    return clique_number_bound(corr, params, params.eps, part_size);
  }
};

}  // namespace

void register_clipper_solver() {
  SolverRegistry::add(
      {"clipper",
       "CLIPPER+ (Fathian & Summers, RA-L 2024) on CLIPPER's weighted consistency graph (Lusk et "
       "al., ICRA 2021): core-number greedy clique, k-core pruning, CLIPPER's projected gradient "
       "ascent with growing penalty d, least-squares fit of the clique",
       [] { return std::make_unique<ClipperSolver>(); }});
}

const ParamFamily& clipper_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "clipper",
      "clipper (CLIPPER+; the graph takes --eps as CLIPPER's epsilon)",
      {bind(&SolverParams::clipper, &ClipperParams::sigma,
            {"clipper-sigma",
             "clipper_sigma",
             "S",
             "kernel width of the pair scores exp(-c^2 / (2 S^2)) [m]; 0 = eps / 2 (CLIPPER's "
             "registration examples: sigma 0.01 with epsilon 0.02)",
             K::real,
             0,
             1e12,
             "a finite value >= 0 (0 = eps / 2)",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::binary,
            {"clipper-binary",
             "clipper_binary",
             "",
             "unweighted affinity, M = adjacency + I (CLIPPER+'s graphs), not CLIPPER's scores",
             K::flag,
             0,
             1,
             "",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::no_kcore,
            {"clipper-no-kcore",
             "clipper_no_kcore",
             "",
             "plain CLIPPER: no core-number heuristic clique, certificate or pruning; the "
             "ascent runs on the whole graph from a random u0 (seeded by --seed)",
             K::flag,
             0,
             1,
             "",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::tol_u,
            {"clipper-tol-u",
             "clipper_tol_u",
             "T",
             "inner loop stops when ||u_new - u|| < T (CLIPPER+ tol_u: 1e-8)",
             K::real,
             0,
             1,
             "a value in [0, 1]",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::tol_f,
            {"clipper-tol-f",
             "clipper_tol_f",
             "T",
             "inner loop stops when the objective changes by less than T (CLIPPER+ tol_F: 1e-9)",
             K::real,
             0,
             1,
             "a value in [0, 1]",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::max_inner,
            {"clipper-max-inner",
             "clipper_max_inner",
             "N",
             "gradient ascent steps per value of d at most (CLIPPER+ maxiniters: 200)",
             K::integer,
             1,
             1e9,
             "an integer >= 1",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::max_outer,
            {"clipper-max-outer",
             "clipper_max_outer",
             "N",
             "increases of the penalty d at most (CLIPPER+ maxoliters: 1000)",
             K::integer,
             1,
             1e9,
             "an integer >= 1",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::max_line_search,
            {"clipper-max-line-search",
             "clipper_max_line_search",
             "N",
             "backtracking steps per gradient step at most (CLIPPER+ maxlsiters: 20)",
             K::integer,
             1,
             1000,
             "an integer in [1, 1000]",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::beta,
            {"clipper-beta",
             "clipper_beta",
             "B",
             "line search: step x B on a failed Armijo test, / sqrt(B) after a passed one "
             "(CLIPPER+ beta: 0.5)",
             K::real,
             1e-6,
             0.999999,
             "a value in (0, 1)",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::armijo,
            {"clipper-armijo",
             "clipper_armijo",
             "A",
             "sufficient increase of the Armijo test, F_new - F >= A grad . (u_new - u) (CLIPPER+ "
             "sigma: 0.01)",
             K::real,
             0,
             0.999999,
             "a value in [0, 1)",
             {},
             {},
             {}}),
       bind(&SolverParams::clipper, &ClipperParams::zero_eps,
            {"clipper-zero-eps",
             "clipper_zero_eps",
             "E",
             "numerical zero of u and of the inconsistent mass C-bar u, and the rounding "
             "threshold: the selection is u_i > E (CLIPPER+ eps: 1e-9)",
             K::real,
             1e-300,
             0.1,
             "a value in (0, 0.1]",
             {},
             {},
             {}})}};
  return family;
}

}  // namespace verifybench
