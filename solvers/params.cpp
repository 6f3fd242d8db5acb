#include "solvers/params.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace verifybench {

const ParamFamily& ransac_param_family();  // ransac_solver.cpp
const ParamFamily& mac_param_family();     // mac_solver.cpp
const ParamFamily& jcbb_param_family();    // jcbb_solver.cpp
const ParamFamily& gnc_param_family();     // gnc_tls_solver.cpp
const ParamFamily& teaser_param_family();  // teaser_solver.cpp
const ParamFamily& sc2_param_family();     // sc2pcr_solver.cpp
const ParamFamily& robin_param_family();     // robin_gnc_solver.cpp
const ParamFamily& quatro_param_family();    // quatro_solver.cpp
const ParamFamily& turboreg_param_family();  // turboreg_solver.cpp
const ParamFamily& clipper_param_family();   // clipper_solver.cpp
const ParamFamily& fastmac_param_family();   // fastmac_solver.cpp

const std::vector<ParamFamily>& param_families() {
  static const std::vector<ParamFamily> families = {
      ransac_param_family(),   mac_param_family(),     jcbb_param_family(),   gnc_param_family(),
      teaser_param_family(),   sc2_param_family(),     robin_param_family(),  quatro_param_family(),
      turboreg_param_family(), clipper_param_family(), fastmac_param_family()};
  return families;
}

std::string default_text(const ParamField& f) {
  return f.kind == ParamField::Kind::flag ? "" : f.text(SolverParams{});
}

namespace {

ParamField number(std::string option, std::string key, std::string value_name, std::string help,
                  ParamField::Kind kind, double min, double max, std::string expected) {
  ParamField f;
  f.option = std::move(option);
  f.key = std::move(key);
  f.value_name = std::move(value_name);
  f.help = std::move(help);
  f.kind = kind;
  f.min = min;
  f.max = max;
  f.expected = std::move(expected);
  return f;
}

ParamFamily make_common_family() {
  using K = ParamField::Kind;
  ParamFamily family{"common", "solvers", {}};
  auto& rows = family.fields;
  rows.push_back(param_row(&SolverParams::eps,
                           number("eps", "eps", "M",
                                  "pair length tolerance of the correspondence graph, Eq. (1) [m]",
                                  K::real, 1e-12, 1e12, "a finite value > 0")));
  ParamField inlier = param_row(&SolverParams::inlier_threshold,
                                number("inlier-threshold", "inlier_threshold", "M",
                                       "consensus residual threshold [m]", K::real, 1e-12, 1e12,
                                       "a finite value > 0"));
  inlier.when_absent = [](SolverParams& p) { p.inlier_threshold = p.eps; };
  inlier.default_note = "eps";
  rows.push_back(inlier);
  rows.push_back(param_row(&SolverParams::min_inliers,
                           number("min-inliers", "min_inliers", "K",
                                  "count rule: accept when inliers >= K; 0 = paper default (5 in "
                                  "3D, 10 in 2D)",
                                  K::integer, 0, 1 << 30, "an integer >= 0 (0 = paper default)")));
  rows.push_back(param_row(&SolverParams::time_limit_s,
                           number("time-limit", "time_limit_s", "S",
                                  "the pair's time budget [s]: the solve, then the pvalue rule's "
                                  "null solves share what is left (a decision the budget cut short "
                                  "is marked provisional); best-so-far past it",
                                  K::real, 1e-6, 1e9, "a value > 0")));
  ParamField graph_mb = number("max-graph-mb", "max_graph_bytes", "MB",
                               "refuse correspondence graphs larger than this", K::integer, 1,
                               1LL << 30, "an integer >= 1");
  graph_mb.get = [](const SolverParams& p) {
    return static_cast<double>(p.max_graph_bytes >> 20);
  };
  graph_mb.set = [](SolverParams& p, double v) {
    p.max_graph_bytes = static_cast<std::size_t>(v) << 20;
  };
  graph_mb.report = [](const SolverParams& p) { return static_cast<double>(p.max_graph_bytes); };
  rows.push_back(graph_mb);
  rows.push_back(param_row(&SolverParams::threads,
                           number("threads", "threads", "T",
                                  "threads for graph construction, clique-bbmc-dec and the pvalue "
                                  "rule's null solves (0 = all cores); results do not depend on it",
                                  K::integer, 0, 1024, "an integer >= 0 (0 = all cores)")));
  return family;
}

}  // namespace

const ParamFamily& common_param_family() {
  static const ParamFamily family = make_common_family();
  return family;
}

std::vector<ParamField> solver_param_rows() {
  std::vector<ParamField> rows = common_param_family().fields;
  for (const ParamFamily& family : param_families()) {
    rows.insert(rows.end(), family.fields.begin(), family.fields.end());
  }
  return rows;
}

namespace {

template <class T>
void require(bool ok, const std::string& field, T value, const std::string& expected) {
  if (ok) return;
  std::ostringstream msg;
  msg << "solver parameter " << field << " = " << value << " is invalid; expected " << expected;
  throw std::invalid_argument(msg.str());
}

}  // namespace

void SolverParams::validate() const {
  require(eps > 0.0 && std::isfinite(eps), "eps", eps, "a finite value > 0");
  require(inlier_threshold > 0.0 && std::isfinite(inlier_threshold), "inlier_threshold",
          inlier_threshold, "a finite value > 0");
  require(min_inliers >= 0, "min_inliers", min_inliers, "an integer >= 0 (0 = paper default)");
  require(time_limit_s > 0.0, "time_limit_s", time_limit_s, "a value > 0");
  require(threads >= 0, "threads", threads, "an integer >= 0 (0 = all cores)");
  for (const ParamFamily& family : param_families()) {
    for (const ParamField& f : family.fields) {
      if (f.kind == ParamField::Kind::flag || f.kind == ParamField::Kind::text) continue;
      const double v = f.get(*this);
      require(std::isfinite(v) && v >= f.min && v <= f.max, f.key, v, f.expected);
    }
  }
}

}  // namespace verifybench
