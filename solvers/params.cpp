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

const std::vector<ParamFamily>& param_families() {
  static const std::vector<ParamFamily> families = {ransac_param_family(), mac_param_family(),
                                                    jcbb_param_family(),   gnc_param_family(),
                                                    teaser_param_family(), sc2_param_family()};
  return families;
}

std::string default_text(const ParamField& f) {
  if (f.kind == ParamField::Kind::flag) return "";
  std::ostringstream out;
  const double v = f.get(SolverParams{});
  if (f.kind == ParamField::Kind::integer) {
    out << static_cast<long long>(v);
  } else {
    out << v;
  }
  return out.str();
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

const char* to_string(AcceptParams::Rule rule) {
  return rule == AcceptParams::Rule::count ? "count" : "pvalue";
}

AcceptParams::Rule parse_accept_rule(const std::string& name) {
  if (name == "pvalue") return AcceptParams::Rule::pvalue;
  if (name == "count") return AcceptParams::Rule::count;
  throw std::invalid_argument("accept rule '" + name + "' is unknown (known: pvalue, count)");
}

void SolverParams::validate() const {
  require(eps > 0.0 && std::isfinite(eps), "eps", eps, "a finite value > 0");
  require(inlier_threshold > 0.0 && std::isfinite(inlier_threshold), "inlier_threshold",
          inlier_threshold, "a finite value > 0");
  require(min_inliers >= 0, "min_inliers", min_inliers, "an integer >= 0 (0 = paper default)");
  require(time_limit_s > 0.0, "time_limit_s", time_limit_s, "a value > 0");
  require(accept.alpha > 0.0 && accept.alpha < 1.0, "alpha", accept.alpha, "a value in (0, 1)");
  require(accept.null_draws >= 2, "null_draws", accept.null_draws, "an integer >= 2");
  require(accept.prior_gate >= 0.0 && accept.prior_gate < 1.0, "prior_gate", accept.prior_gate,
          "a value in [0, 1) (0 = no gate)");
  require(accept.max_null_draws >= 0, "max_null_draws", accept.max_null_draws, "an integer >= 0");
  require(threads >= 0, "threads", threads, "an integer >= 0 (0 = all cores)");
  for (const ParamFamily& family : param_families()) {
    for (const ParamField& f : family.fields) {
      if (f.kind == ParamField::Kind::flag) continue;
      const double v = f.get(*this);
      require(std::isfinite(v) && v >= f.min && v <= f.max, f.key, v, f.expected);
    }
  }
}

}  // namespace verifybench
