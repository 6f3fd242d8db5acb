#include "acceptance/accept_params.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace verifybench {

namespace {

using Row = ParamRow<AcceptParams>;
using K = Row::Kind;

Row number(std::string option, std::string key, std::string value_name, std::string help, K kind,
           double min, double max, std::string expected) {
  Row r;
  r.option = std::move(option);
  r.key = std::move(key);
  r.value_name = std::move(value_name);
  r.help = std::move(help);
  r.kind = kind;
  r.min = min;
  r.max = max;
  r.expected = std::move(expected);
  return r;
}

std::vector<Row> make_rows() {
  std::vector<Row> rows;
  Row rule = number("accept", "accept_rule", "RULE",
                    "accept rule: pvalue (p < alpha against a permutation null of the pair) or "
                    "count (inliers >= --min-inliers, the paper's rule)",
                    K::text, 0, 0, "pvalue or count");
  rule.get_text = [](const AcceptParams& p) { return std::string(to_string(p.rule)); };
  rule.set_text = [](AcceptParams& p, const std::string& v) { p.rule = parse_accept_rule(v); };
  rows.push_back(rule);
  rows.push_back(param_row(&AcceptParams::alpha,
                           number("alpha", "alpha", "A", "pvalue rule: accept when p < A", K::real,
                                  1e-300, 0.999999, "a value in (0, 1)")));
  rows.push_back(param_row(&AcceptParams::null_draws,
                           number("null-draws", "null_draws", "K",
                                  "pvalue rule: permuted sets the null is fitted on (each one more "
                                  "solve)",
                                  K::integer, 2, 100000, "an integer >= 2")));
  rows.push_back(param_row(&AcceptParams::max_null_draws,
                           number("max-null-draws", "max_null_draws", "K",
                                  "pvalue rule: where the range of p after --null-draws draws still "
                                  "holds alpha, draw on until it does not or K draws ran in all "
                                  "(<= --null-draws: never)",
                                  K::integer, 0, 100000, "an integer >= 0")));
  rows.push_back(param_row(&AcceptParams::prior_gate,
                           number("prior-gate", "prior_gate", "C",
                                  "pvalue rule, sets with a pose prior: accept only motions inside "
                                  "the prior's chi-square gate at confidence C (0 = no gate)",
                                  K::real, 0.0, 0.999999999, "a value in [0, 1) (0 = no gate)")));
  return rows;
}

}  // namespace

const std::vector<ParamRow<AcceptParams>>& accept_param_rows() {
  static const std::vector<Row> rows = make_rows();
  return rows;
}

const char* to_string(AcceptParams::Rule rule) {
  return rule == AcceptParams::Rule::count ? "count" : "pvalue";
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
    if (v >= r.min && v <= r.max && (r.kind != K::integer || v == std::floor(v))) continue;
    std::ostringstream msg;
    msg << "accept parameter " << r.key << " = " << v << " is invalid; expected " << r.expected;
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace verifybench
