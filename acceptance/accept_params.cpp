#include "acceptance/accept_params.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace verifybench {

namespace {

using Row = ParamRow<AcceptParams>;
using K = Row::Kind;

std::vector<Row> make_rows() {
  using P = AcceptParams;
  return {
      text_row<P>(
          "accept", "accept_rule", "RULE",
          "accept rule: pvalue (p < alpha against a permutation null of the pair) or count "
          "(inliers >= --min-inliers, the paper's rule)",
          [](const P& p) { return std::string(to_string(p.rule)); },
          [](P& p, const std::string& v) { p.rule = parse_accept_rule(v); }, "pvalue or count"),
      field_row(&P::alpha, "alpha", "alpha", "A", "pvalue rule: accept when p < A", 1e-300,
                0.999999, "a value in (0, 1)"),
      field_row(&P::null_draws, "null-draws", "null_draws", "K",
                "pvalue rule: permuted sets the null is fitted on (each one more solve)", 2,
                100000, "an integer >= 2"),
      field_row(&P::max_null_draws, "max-null-draws", "max_null_draws", "K",
                "pvalue rule: where the range of p after --null-draws draws still holds alpha, "
                "draw on until it does not or K draws ran in all (<= --null-draws: never)",
                0, 100000, "an integer >= 0"),
      field_row(&P::prior_gate, "prior-gate", "prior_gate", "C",
                "pvalue rule, sets with a pose prior: accept only motions inside the prior's "
                "chi-square gate at confidence C (0 = no gate)",
                0.0, 0.999999999, "a value in [0, 1) (0 = no gate)"),
      field_row(&P::runner_up_alpha, "runner-up-alpha", "runner_up_alpha", "A",
                "pvalue rule: reject a pair whose rival motions (the same solver again, or clique "
                "for gnc-tls and robin-gnc, on the correspondences the accepted motion and the earlier rivals leave unexplained; "
                "each with p < A under the pair's null and an excess over the null's location "
                "at least 0.4 of the pair's) hold together as many inliers as the accepted one: "
                "a rigid alias (0 = no runner-up test; -1 = the rule's default: --alpha where no "
                "dense check runs, 0 where one does)",
                P::kRunnerUpDefault, 0.999999,
                "a value in [0, 1), or -1 (the rule's default)")};
}

}  // namespace

const std::vector<ParamRow<AcceptParams>>& accept_param_rows() {
  static const std::vector<Row> rows = make_rows();
  return rows;
}

const char* to_string(AcceptParams::Rule rule) {
  return rule == AcceptParams::Rule::count ? "count" : "pvalue";
}

double AcceptParams::runner_up_level() const {
  if (rule != Rule::pvalue) return 0.0;
  return runner_up_alpha == kRunnerUpDefault ? alpha : runner_up_alpha;
}

void AcceptParams::resolve_runner_up(bool dense_check_runs) {
  if (runner_up_alpha != kRunnerUpDefault) return;
  runner_up_alpha = rule == Rule::pvalue && !dense_check_runs ? alpha : 0.0;
}

AcceptParams::Rule parse_accept_rule(const std::string& name) {
  if (name == "pvalue") return AcceptParams::Rule::pvalue;
  if (name == "count") return AcceptParams::Rule::count;
  throw std::invalid_argument("accept rule '" + name + "' is unknown (known: pvalue, count)");
}

void AcceptParams::validate() const {
  // The rows' ranges, which are the CLI's and Python's (alpha in (0, 1), draws >= 2, gate in [0, 1)).
  for (const Row& r : accept_param_rows()) {
    if (r.kind == K::text) continue;
    const double v = r.get(*this);
    const bool in_range = v >= r.min && v <= r.max && (r.kind != K::integer || v == std::floor(v));
    // runner_up_alpha: [0, 1) or exactly the default's -1.
    const bool sentinel_gap = r.key == "runner_up_alpha" && v < 0.0 && v != AcceptParams::kRunnerUpDefault;
    if (in_range && !sentinel_gap) continue;
    std::ostringstream msg;
    msg << "accept parameter " << r.key << " = " << v << " is invalid; expected " << r.expected;
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace verifybench
