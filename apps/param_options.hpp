#pragma once
// Rows (core/param_rows.hpp) on the command line: each row becomes one option bound to the struct
// the command fills (its default and range in --help, its value set while parsing); the report's
// block is the rows' values by key; README's tables are the rows as markdown.
#include <nlohmann/json.hpp>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include "apps/options.hpp"
#include "core/param_rows.hpp"

namespace verifybench::cli {

/// Each row becomes one option bound to `p`: its default in --help is p's value now, a given value
/// is read with the row's kind and range and set into p while the line is parsed, and a row not
/// given derives its value (when_absent) once every given one is set. `p` must outlive parse().
template <class P>
void add_rows(Options& o, const std::vector<ParamRow<P>>& rows, P& p) {
  using Kind = typename ParamRow<P>::Kind;
  for (const auto& r : rows) {
    std::string help = r.help;
    if (!r.expected.empty()) {
      help += ": " + r.expected;
    } else if (!r.range().empty()) {
      help += ", in " + r.range();
    }
    std::function<void()> absent;
    if (r.when_absent) absent = [r, &p] { r.when_absent(p); };
    if (r.kind == Kind::flag) {
      o.flag(r.option, help, [r, &p] { r.set(p, 1.0); }, absent);
      continue;
    }
    o.bind(r.option, r.value_name, r.text(p), help,
           [r, &p](const std::string& v) {
             switch (r.kind) {
               case Kind::integer:
                 r.set(p, static_cast<double>(Options::integer_value(
                              r.option, v, static_cast<long long>(r.min),
                              static_cast<long long>(r.max))));
                 break;
               case Kind::real:
                 if (r.infinite_ok && v == "inf") {
                   r.set(p, std::numeric_limits<double>::infinity());
                 } else {
                   r.set(p, Options::real_value(r.option, v, r.min, r.max));
                 }
                 break;
               case Kind::text:
                 try {
                   r.set_text(p, v);
                 } catch (const std::invalid_argument& e) {
                   throw UsageError("--" + r.option + ": " + e.what());
                 }
                 break;
               case Kind::flag:
                 break;
             }
           },
           absent);
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
