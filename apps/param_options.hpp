#pragma once
// Rows (core/param_rows.hpp) on the command line: each row becomes one option with its default
// (taken from the struct the command starts from) and range in --help; a given option is read
// with the row's range and set; the report's block is the rows' values by key.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "apps/options.hpp"
#include "core/param_rows.hpp"

namespace verifybench::cli {

template <class P>
void add_rows(Options& o, const std::vector<ParamRow<P>>& rows, const P& defaults) {
  using Kind = typename ParamRow<P>::Kind;
  for (const auto& r : rows) {
    const bool flag = r.kind == Kind::flag;
    std::string help = r.help;
    if (!r.expected.empty()) {
      help += ": " + r.expected;
    } else if (!r.range().empty()) {
      help += ", in " + r.range();
    }
    o.add(r.option, flag ? "" : r.value_name, flag ? "" : r.text(defaults), help);
  }
}

/// Sets `p` from the options given (the rest keep p's values); UsageError names the option.
template <class P>
void read_rows(const Options& o, const std::vector<ParamRow<P>>& rows, P& p) {
  using Kind = typename ParamRow<P>::Kind;
  for (const auto& r : rows) {
    if (!o.given(r.option)) {
      if (r.when_absent) r.when_absent(p);
      continue;
    }
    switch (r.kind) {
      case Kind::flag:
        r.set(p, 1.0);
        break;
      case Kind::integer:
        r.set(p, static_cast<double>(o.integer(r.option, static_cast<long long>(r.min),
                                               static_cast<long long>(r.max))));
        break;
      case Kind::real:
        if (r.infinite_ok && o.text(r.option) == "inf") {
          r.set(p, std::numeric_limits<double>::infinity());
        } else {
          r.set(p, o.real(r.option, r.min, r.max));
        }
        break;
      case Kind::text:
        try {
          r.set_text(p, o.text(r.option));
        } catch (const std::invalid_argument& e) {
          throw UsageError("--" + r.option + ": " + e.what());
        }
        break;
    }
  }
}

/// The rows as markdown table lines, one per option: `| \`--option V\` | default | what (range) |`,
/// the default read from `defaults` as --help shows it ("off" for a flag); README's option tables
/// are these lines (`verifybench list --settings-md`, checked by a test), so they cannot drift.
template <class P>
std::string rows_markdown(const std::vector<ParamRow<P>>& rows, const P& defaults) {
  using Kind = typename ParamRow<P>::Kind;
  std::string out;
  for (const auto& r : rows) {
    const bool flag = r.kind == Kind::flag;
    std::string what = r.help;
    if (!r.expected.empty()) {
      what += ": " + r.expected;
    } else if (!r.range().empty()) {
      what += ", in " + r.range();
    }
    std::string cell;
    for (char c : what) cell += c == '|' ? std::string("\\|") : std::string(1, c);
    const std::string value = flag ? "off" : r.text(defaults);
    out += "| `--" + r.option + (flag ? "" : " " + r.value_name) + "` | " +
           (value.empty() ? "-" : value) + " | " + cell + " |\n";
  }
  return out;
}

/// {key: value} of every row (an infinite real as null, a flag as a bool).
template <class P>
nlohmann::json rows_json(const std::vector<ParamRow<P>>& rows, const P& p) {
  using Kind = typename ParamRow<P>::Kind;
  nlohmann::json j = nlohmann::json::object();
  for (const auto& r : rows) {
    switch (r.kind) {
      case Kind::text:
        j[r.key] = r.get_text(p);
        break;
      case Kind::flag:
        j[r.key] = r.get(p) != 0.0;
        break;
      case Kind::integer:
        j[r.key] = static_cast<long long>(r.report ? r.report(p) : r.get(p));
        break;
      case Kind::real: {
        const double v = r.report ? r.report(p) : r.get(p);
        j[r.key] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
        break;
      }
    }
  }
  return j;
}

}  // namespace verifybench::cli
