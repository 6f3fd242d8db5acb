#pragma once
// One parameter, one place: a setting a user can change is one row, declared beside the struct
// that owns it (its CLI option, report key, range and help); the command line, the validation and
// the report's `parameters` block are made from the rows (apps/param_options.hpp). The rows of a
// struct P read and write a P; the defaults are those of the P a command starts from, so two
// commands that share rows share names and ranges even where their defaults differ.
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace verifybench {

template <class P>
struct ParamRow {
  enum class Kind { real, integer, flag, text };
  std::string option;      ///< CLI option without the dashes: "iss-salient-radius"; with '-' as
                           ///< '_' the Python keyword
  std::string key;         ///< report key: "iss_salient_radius_m"
  std::string value_name;  ///< shown in --help ("M"); empty for a flag
  std::string help;
  Kind kind = Kind::real;
  double min = 0.0, max = 0.0;  ///< inclusive range of a real or integer
  std::string expected;         ///< the range in words for messages ("an integer >= 1"); optional
  /// real, integer, flag (0 / 1): the value in P, and its setter.
  std::function<double(const P&)> get;
  std::function<void(P&, double)> set;
  /// The value the report records, when it is not get's (a size in MB reported in bytes).
  std::function<double(const P&)> report;
  bool infinite_ok = false;  ///< real: "inf" stands for no limit
  /// text: the value in P, and a setter that throws std::invalid_argument for a bad text.
  std::function<std::string(const P&)> get_text;
  std::function<void(P&, const std::string&)> set_text;
  /// When the option is not given: derive the value from the others (inlier threshold = eps).
  std::function<void(P&)> when_absent;
  std::string default_note;  ///< --help's default in words where it is derived ("eps")

  /// The Python keyword: the option with '-' as '_'.
  std::string keyword() const {
    std::string k = option;
    for (char& c : k) {
      if (c == '-') c = '_';
    }
    return k;
  }
  /// The value of `p` as text ("0.5", "1000", "inf", "nearest"; "" for an unset flag); a real row
  /// whose one option sets two fields may show both through get_text ("0.5; fpfh 0.3").
  std::string text(const P& p) const {
    if (!default_note.empty()) return default_note;
    if (get_text) return get_text(p);
    const double v = get(p);
    if (kind == Kind::flag) return v != 0.0 ? "on" : "";
    if (std::isinf(v)) return "inf";
    std::ostringstream out;
    if (kind == Kind::integer) {
      out << static_cast<long long>(v);
    } else {
      out << v;
    }
    return out.str();
  }
  /// The range in words, for messages and the README: "[0.000001, 1000000]".
  std::string range() const {
    if (kind == Kind::flag || kind == Kind::text) return "";
    std::ostringstream out;
    if (kind == Kind::integer) {
      out << "[" << static_cast<long long>(min) << ", " << static_cast<long long>(max) << "]";
    } else {
      out << "[" << min << ", " << max << "]";
    }
    if (infinite_ok) out << " or inf";
    return out.str();
  }
  /// Throws std::invalid_argument naming the key and the value when p's value is out of range.
  void check(const P& p) const {
    if (kind == Kind::text || kind == Kind::flag) return;
    const double v = get(p);
    const bool ok = (infinite_ok && v == std::numeric_limits<double>::infinity()) ||
                    (std::isfinite(v) && v >= min && v <= max &&
                     (kind != Kind::integer || v == std::floor(v)));
    if (!ok) {
      std::ostringstream msg;
      msg << key << " = " << v << " is outside " << range();
      throw std::invalid_argument(msg.str());
    }
  }
};

/// A real or integer row bound to `p.*member`.
template <class P, class T>
ParamRow<P> param_row(T P::*member, ParamRow<P> row) {
  row.get = [=](const P& p) { return static_cast<double>(p.*member); };
  row.set = [=](P& p, double v) { p.*member = static_cast<T>(v); };
  return row;
}

/// A row bound to `p.*member` from its words: the kind follows the member's type (bool: a flag,
/// an integer type: integer, else real); `expected` is the range in words for messages.
template <class P, class T>
ParamRow<P> field_row(T P::*member, std::string option, std::string key, std::string value_name,
                      std::string help, double min = 0.0, double max = 0.0,
                      std::string expected = "") {
  ParamRow<P> row;
  row.option = std::move(option);
  row.key = std::move(key);
  row.value_name = std::move(value_name);
  row.help = std::move(help);
  using K = typename ParamRow<P>::Kind;
  row.kind = std::is_same_v<T, bool> ? K::flag : std::is_integral_v<T> ? K::integer : K::real;
  row.min = min;
  row.max = max;
  row.expected = std::move(expected);
  return param_row(member, std::move(row));
}

/// A text row: `get` reads the value as text, `set` writes it (throwing std::invalid_argument for
/// a bad text, which the CLI reports with the option).
template <class P>
ParamRow<P> text_row(std::string option, std::string key, std::string value_name, std::string help,
                     std::function<std::string(const P&)> get,
                     std::function<void(P&, const std::string&)> set, std::string expected = "") {
  ParamRow<P> row;
  row.option = std::move(option);
  row.key = std::move(key);
  row.value_name = std::move(value_name);
  row.help = std::move(help);
  row.kind = ParamRow<P>::Kind::text;
  row.expected = std::move(expected);
  row.get_text = std::move(get);
  row.set_text = std::move(set);
  return row;
}

/// A row bound to `p.*outer.*member` (a field of a nested struct).
template <class P, class S, class T>
ParamRow<P> param_row(S P::*outer, T S::*member, ParamRow<P> row) {
  row.get = [=](const P& p) { return static_cast<double>(p.*outer.*member); };
  row.set = [=](P& p, double v) { p.*outer.*member = static_cast<T>(v); };
  return row;
}

/// The rows of a struct as rows of the struct that holds it at `member` (the same options, keys,
/// ranges and help): several owners' rows read through one table (the Python binding's keywords).
template <class Outer, class Inner>
std::vector<ParamRow<Outer>> lift_rows(const std::vector<ParamRow<Inner>>& rows,
                                       Inner Outer::*member) {
  std::vector<ParamRow<Outer>> out;
  for (const ParamRow<Inner>& r : rows) {
    ParamRow<Outer> o;
    o.option = r.option;
    o.key = r.key;
    o.value_name = r.value_name;
    o.help = r.help;
    o.kind = static_cast<typename ParamRow<Outer>::Kind>(r.kind);
    o.min = r.min;
    o.max = r.max;
    o.expected = r.expected;
    o.infinite_ok = r.infinite_ok;
    o.default_note = r.default_note;
    if (r.get) o.get = [g = r.get, member](const Outer& p) { return g(p.*member); };
    if (r.set) o.set = [s = r.set, member](Outer& p, double v) { s(p.*member, v); };
    if (r.report) o.report = [g = r.report, member](const Outer& p) { return g(p.*member); };
    if (r.get_text) {
      o.get_text = [g = r.get_text, member](const Outer& p) { return g(p.*member); };
    }
    if (r.set_text) {
      o.set_text = [s = r.set_text, member](Outer& p, const std::string& v) { s(p.*member, v); };
    }
    if (r.when_absent) o.when_absent = [w = r.when_absent, member](Outer& p) { w(p.*member); };
    out.push_back(std::move(o));
  }
  return out;
}

/// Every row's check on `p`.
template <class P>
void check_rows(const std::vector<ParamRow<P>>& rows, const P& p) {
  for (const auto& r : rows) r.check(p);
}

}  // namespace verifybench
