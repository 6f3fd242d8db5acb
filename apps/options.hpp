#pragma once
// A small command-line option parser: declared options only, "--name value" or "--name=value",
// strict typed getters whose errors name the option and the value.
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace verifybench {

class Options {
 public:
  /// `value_name` empty declares a flag; `fallback` is the default text shown in --help.
  Options& add(const std::string& name, const std::string& value_name, const std::string& fallback,
               const std::string& help);

  /// Starts a titled group: the options added next are listed under it in --help.
  Options& group(const std::string& title) {
    order_.push_back("\n" + title);
    return *this;
  }
  /// Accepts arguments that are not options (e.g. input files), kept in positional().
  Options& allow_positional(const std::string& name) {
    positional_name_ = name;
    return *this;
  }
  /// Throws UsageError on an unknown option (naming the nearest known one), a missing value, a
  /// repeated option or a stray argument. `-o` and `-q` stand for --out and --quiet where declared.
  void parse(const std::vector<std::string>& args);
  const std::vector<std::string>& positional() const { return positional_; }
  /// parse(); then, when --help was given, prints `usage` and the options and returns true.
  bool parse_or_help(const std::vector<std::string>& args, const std::string& usage);
  std::string help() const;
  bool help_requested() const { return help_; }

  bool flag(const std::string& name) const;
  bool given(const std::string& name) const { return values_.count(name) > 0; }
  std::string text(const std::string& name) const;  ///< the value or its default; "" when neither
  std::string required(const std::string& name) const;
  double real(const std::string& name, double min, double max) const;
  long long integer(const std::string& name, long long min, long long max) const;
  std::uint64_t seed(const std::string& name) const;
  std::vector<std::string> list(
      const std::string& name) const;  ///< comma-separated, non-empty items

 private:
  struct Spec {
    std::string value_name, fallback, help;
  };
  [[noreturn]] void bad(const std::string& name, const std::string& value,
                        const std::string& why) const;
  std::vector<std::string> order_;
  std::map<std::string, Spec> specs_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positional_;
  std::string positional_name_;
  bool help_ = false;
};

/// Parses "start:stop:step" (stop included) or "a,b,c" into values within [min, max].
std::vector<double> parse_range(const std::string& option, const std::string& text, double min,
                                double max);

/// Strict number parsing; throws UsageError naming `what` and the text.
double parse_real(const std::string& what, const std::string& text);
long long parse_integer(const std::string& what, const std::string& text);

}  // namespace verifybench
