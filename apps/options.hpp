#pragma once
// The command line, bound to the fields it sets: each option is declared with the field (or the
// parameter row, apps/param_options.hpp) it writes, its default in --help is that field's value
// at declaration, and CLI11 calls the option's setter while it parses: "--name value" or
// "--name=value", strictly parsed (no NaN, inf or trailing text), range-checked, the error naming
// the option and the value. No value is kept as text for a later lookup.
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.hpp"

namespace verifybench {

class Options {
 public:
  /// Reads one given value into its field; throws UsageError naming the option and the value.
  using Set = std::function<void(const std::string& value)>;

  /// Starts a titled group: the options declared next are listed under it in --help.
  Options& group(const std::string& title) {
    order_.push_back("\n" + title);
    return *this;
  }
  /// Arguments that are not options (input files) go into `into`.
  Options& allow_positional(const std::string& name, std::vector<std::string>& into) {
    positional_name_ = name;
    positional_ = &into;
    return *this;
  }

  /// The general form: `set` reads the value when given; `absent` (optional) runs after parsing
  /// when the option was not given (a default derived from other options); `shown` is --help's
  /// default.
  Options& bind(const std::string& name, const std::string& value_name, const std::string& shown,
                const std::string& help, Set set, std::function<void()> absent = {});
  /// A flag: `on` runs when given, `absent` (optional) after parsing when it was not.
  Options& flag(const std::string& name, const std::string& help, std::function<void()> on,
                std::function<void()> absent = {});
  Options& flag(const std::string& name, bool& field, const std::string& help) {
    return flag(name, help, [&field] { field = true; });
  }
  /// A finite real in [min, max].
  Options& real(const std::string& name, double& field, const std::string& value_name,
                const std::string& help, double min, double max);
  /// An integer in [min, max], into an integral field of any width.
  template <class Int>
  Options& integer(const std::string& name, Int& field, const std::string& value_name,
                   const std::string& help, long long min, long long max) {
    static_assert(std::is_integral_v<Int>, "an integer option binds an integral field");
    return bind(name, value_name, std::to_string(field), help,
                [&field, name, min, max](const std::string& v) {
                  field = static_cast<Int>(integer_value(name, v, min, max));
                });
  }
  /// An unsigned 64-bit seed.
  Options& seed(const std::string& name, std::uint64_t& field, const std::string& help);
  /// Any text (a path, a name checked later against its registry).
  Options& text(const std::string& name, std::string& field, const std::string& value_name,
                const std::string& help);
  /// Comma-separated, non-empty items.
  Options& list(const std::string& name, std::vector<std::string>& field,
                const std::string& value_name, const std::string& help);

  /// Sets every given option's field, then runs the `absent` hooks of those not given (neither
  /// when --help is among the arguments: then only the help is printed). Throws
  /// UsageError on an unknown option (naming the nearest known one), a missing value, a repeated
  /// option, a stray argument or a value its setter refuses. `-o` and `-q` stand for --out and
  /// --quiet where declared.
  void parse(const std::vector<std::string>& args);
  /// parse(); then, when --help was given, prints `usage` and the options and returns true.
  bool parse_or_help(const std::vector<std::string>& args, const std::string& usage);
  std::string help() const;
  bool given(const std::string& name) const { return given_.count(name) > 0; }
  /// UsageError "option --name is required" when it was not given, or given an empty value.
  void require(const std::string& name) const;

  /// The strict readers the setters use (messages: "--name: 'text' is outside [min, max]").
  static double real_value(const std::string& name, const std::string& text, double min,
                           double max);
  static long long integer_value(const std::string& name, const std::string& text, long long min,
                                 long long max);
  static std::vector<std::string> list_value(const std::string& name, const std::string& text);

 private:
  struct Spec {
    std::string value_name, shown, help;
    Set set;                      ///< an option with a value
    std::function<void()> on;     ///< a flag
    std::function<void()> absent;
  };
  std::vector<std::string> order_;
  std::map<std::string, Spec> specs_;
  std::set<std::string> given_;
  std::set<std::string> empty_;  ///< given with an empty value
  std::vector<std::string>* positional_ = nullptr;
  std::string positional_name_;
  bool help_ = false;
};

/// A number as --help shows it ("0.01", "1e+09", "inf").
inline std::string shown_number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

/// Parses "start:stop:step" (stop included) or "a,b,c" into values within [min, max].
std::vector<double> parse_range(const std::string& option, const std::string& text, double min,
                                double max);

/// Strict number parsing; throws UsageError naming `what` and the text.
double parse_real(const std::string& what, const std::string& text);
long long parse_integer(const std::string& what, const std::string& text);

}  // namespace verifybench
