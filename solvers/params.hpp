#pragma once
// Solver parameters: the options every solver shares, plus one plain struct per solver family.
// A family's fields are declared once, as ParamField rows in the family's own solver file
// (ransac_solver.cpp, mac_solver.cpp, jcbb_solver.cpp, ...); the CLI options with their defaults
// and ranges, the validation and the report's JSON are all made from those rows.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/param_rows.hpp"
#include "solvers/robin_gnc_params.hpp"
#include "solvers/quatro_params.hpp"
#include "solvers/turboreg_params.hpp"
#include "solvers/clipper_params.hpp"
#include "solvers/fastmac_params.hpp"

namespace verifybench {

struct RansacParams {
  int iterations = 10000;     ///< fixed count, or the cap of the adaptive count
  bool adaptive = false;      ///< `ransac`: stop at k = log(1-p) / log(1-w^s)
  double confidence = 0.999;  ///< p of the adaptive count, in (0, 1)
};

struct MacParams {
  long long max_cliques = 1000000;  ///< stop enumerating maximal cliques after this many
  int min_clique = 3;               ///< smallest maximal clique that makes a hypothesis
};

struct JcbbParams {
  double sigma = 0.0;        ///< per-axis point noise sigma [m]; 0 = inlier_threshold / 3
  double confidence = 0.95;  ///< level of the chi-square gates, in (0, 1)
};

/// Graduated non-convexity with the truncated least squares cost (Yang et al., RA-L 2020): the
/// `gnc-tls` solver, and the rotation stage of `teaser` (TEASER++'s rotation_gnc_* settings).
struct GncParams {
  int max_iterations = 100;      ///< GNC iterations (weight updates) at most
  double mu_factor = 1.4;        ///< mu <- mu_factor * mu after each update, > 1
  double cost_threshold = 1e-6;  ///< stop when the weighted cost changes by less [m^2]
};

/// `teaser` (Yang, Shi, Carlone, T-RO 2020): how the inliers of the pairwise graph are selected.
struct TeaserParams {
  static constexpr int kExact = 0, kHeuristic = 1, kKcore = 2;
  int inlier_selection = kExact;    ///< 0 = max clique, 1 = greedy clique, 2 = max k-core
  double kcore_threshold = 0.5;     ///< kcore: max k-core only when its core > this * n
  bool complete_tim_graph = false;  ///< rotation on all pairs of the selection, not a chain
};

/// `sc2-pcr` (Chen et al., CVPR 2022), defaults from the authors' 3DMatch and KITTI configs.
struct Sc2Params {
  double seed_ratio = 0.2;     ///< at most this fraction of the correspondences become seeds
  double nms_radius = 0.1;     ///< seed non-maximum suppression radius in the source [m]
  int k1 = 30;                 ///< first-stage consensus set: the seed's k1 best by SC2
  int k2 = 20;                 ///< second-stage set: the k2 best by SC2 within the first
  int power_iterations = 10;   ///< power iterations of the spectral scores
  int refine_iterations = 20;  ///< reweighted refits of the final motion at most
};

struct SolverParams {
  double eps = 0.1;  ///< pair length tolerance of the correspondence graph, Eq. (1) [m]
  double inlier_threshold = 0.1;  ///< residual ||T m - q|| of a consensus inlier [m]
  int min_inliers = 0;  ///< accept when |inliers| >= this; 0 = paper default (5 in 3D, 10 in 2D)
  double time_limit_s = 60.0;  ///< wall-clock limit of the search; best-so-far is returned past it
  std::uint64_t seed = 1;      ///< seed of every random draw a solver makes
  std::size_t max_graph_bytes = std::size_t{4} << 30;  ///< refuse larger correspondence graphs
  int threads = 1;  ///< worker threads (0 = all cores); results do not depend on it
  RansacParams ransac;
  MacParams mac;
  JcbbParams jcbb;
  GncParams gnc;
  TeaserParams teaser;
  Sc2Params sc2;
  RobinParams robin;
  QuatroParams quatro;
  TurboRegParams turboreg;
  ClipperParams clipper;
  FastMacParams fastmac;

  /// Throws std::invalid_argument naming the field and the bad value.
  void validate() const;
  /// min_inliers with the paper's per-dimension default applied.
  int accept_threshold(int dim) const {
    return min_inliers > 0 ? min_inliers : (dim == 2 ? 10 : 5);
  }
  double jcbb_point_sigma() const { return jcbb.sigma > 0.0 ? jcbb.sigma : inlier_threshold / 3.0; }
};

/// One setting of the solvers as a row (core/param_rows.hpp): its CLI option, report key, Python
/// keyword, range, help and default (a default SolverParams' value) in one place.
using ParamField = ParamRow<SolverParams>;

struct ParamFamily {
  std::string name;   ///< "ransac"
  std::string title;  ///< heading of the family's options in --help
  std::vector<ParamField> fields;
};

/// The positional form a family declares a row in (the first fields of ParamField, in order).
struct ParamSpec {
  std::string option, key, value_name, help;
  ParamField::Kind kind = ParamField::Kind::real;
  double min = 0.0, max = 0.0;
  std::string expected;
  std::function<double(const SolverParams&)> get;
  std::function<void(SolverParams&, double)> set;
  std::function<double(const SolverParams&)> report;
};

/// Binds a field to `params.*family.*member`; the default shown in --help is the member's value in
/// a default SolverParams.
template <class Family, class T>
ParamField bind(Family SolverParams::*family, T Family::*member, const ParamSpec& spec) {
  ParamField f;
  f.option = spec.option;
  f.key = spec.key;
  f.value_name = spec.value_name;
  f.help = spec.help;
  f.kind = spec.kind;
  f.min = spec.min;
  f.max = spec.max;
  f.expected = spec.expected;
  f.report = spec.report;
  f.get = [=](const SolverParams& p) { return static_cast<double>(p.*family.*member); };
  f.set = [=](SolverParams& p, double v) { p.*family.*member = static_cast<T>(v); };
  return f;
}

/// The settings every solver shares (eps, inlier threshold, min inliers (the count rule's K, which
/// solvers use), the pair's time budget, the graph cap, threads), declared once in params.cpp (the
/// accept rule's own settings are acceptance/accept_params.hpp's); then every family, in --help
/// order (ransac, mac, jcbb, gnc, teaser, sc2, ...).
const ParamFamily& common_param_family();
const std::vector<ParamFamily>& param_families();
/// The common rows, then every family's: what the CLI, the report and Python's solve() take.
std::vector<ParamField> solver_param_rows();

/// The default of a field as --help shows it ("10000", "0.999"; "" for a flag).
std::string default_text(const ParamField& f);

}  // namespace verifybench
