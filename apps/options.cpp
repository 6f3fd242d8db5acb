#include "apps/options.hpp"

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "core/suggest.hpp"

namespace verifybench {

double parse_real(const std::string& what, const std::string& text) {
  const ParsedReal v = parse_real_token(text);
  if (v.error != NumberError::none)
    throw UsageError(what + ": '" + text + "' is not a finite number");
  return v.value;
}

long long parse_integer(const std::string& what, const std::string& text) {
  const auto v = parse_integer_token(text);
  if (!v) throw UsageError(what + ": '" + text + "' is not an integer");
  return *v;
}

Options& Options::add(const std::string& name, const std::string& value_name,
                      const std::string& fallback, const std::string& help) {
  order_.push_back(name);
  specs_[name] = {value_name, fallback, help};
  return *this;
}

void Options::parse(const std::vector<std::string>& given_args) {
  // Short aliases users expect: -o for --out, -q for --quiet, where the command has them.
  std::vector<std::string> args;
  for (const std::string& arg : given_args) {
    const bool out = arg == "-o" && specs_.count("out"),
               quiet = arg == "-q" && specs_.count("quiet");
    args.push_back(out ? "--out" : quiet ? "--quiet" : arg);
  }
  // CLI11 does the splitting ("--name value", "--name=value", positionals, help); the checks it
  // words differently come first, so every message names the option as the rest of the tool does.
  std::map<std::string, int> seen;
  for (const std::string& arg : args) {
    if (arg.rfind("--", 0) != 0 || arg == "--help") continue;
    const std::string name =
        arg.substr(2, arg.find('=') == std::string::npos ? std::string::npos : arg.find('=') - 2);
    const auto spec = specs_.find(name);
    if (spec == specs_.end()) {
      std::vector<std::string> names;
      for (const auto& [known, unused] : specs_) names.push_back(known);
      const std::string near = nearest_name(name, names);
      throw UsageError("unknown option '--" + name + "' (" +
                       (near.empty() ? "" : "did you mean --" + near + "?; ") + "see --help)");
    }
    if (++seen[name] > 1) throw UsageError("option --" + name + " given twice");
    if (spec->second.value_name.empty() && arg.find('=') != std::string::npos) {
      throw UsageError("option --" + name + " takes no value");
    }
  }
  CLI::App app;
  app.set_help_flag();  // --help is ours: it prints the grouped help below
  app.add_flag("-h,--help", help_);
  std::map<std::string, std::string> given;
  std::map<std::string, bool> flags;
  for (const auto& name : order_) {
    if (name[0] == '\n') continue;
    const Spec& spec = specs_.at(name);
    if (spec.value_name.empty()) {
      app.add_flag("--" + name, flags[name]);
    } else {
      app.add_option("--" + name, given[name])->allow_extra_args(false);
    }
  }
  if (!positional_name_.empty()) app.add_option(positional_name_, positional_);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 pops from the back
  try {
    app.parse(reversed);
  } catch (const CLI::ExtrasError&) {
    const auto extra = app.remaining();
    throw UsageError("unexpected argument '" + (extra.empty() ? std::string("?") : extra.front()) +
                     "'");
  } catch (const CLI::ArgumentMismatch& e) {
    const std::string what = e.what();  // "--NAME: 1 required TEXT missing"
    throw UsageError("option " + what.substr(0, what.find(':')) + " needs a value");
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
  for (const auto& [name, on] : flags) {
    if (on) values_[name] = "1";
  }
  for (const auto& [name, value] : given) {
    if (app.count("--" + name) > 0) values_[name] = value;
  }
}

bool Options::parse_or_help(const std::vector<std::string>& args, const std::string& usage) {
  parse(args);
  if (help_) std::cout << usage << help();
  return help_;
}

std::string Options::help() const {
  std::ostringstream out;
  for (const auto& name : order_) {
    if (name[0] == '\n') {  // a group heading
      out << name.substr(1) << ":\n";
      continue;
    }
    const Spec& s = specs_.at(name);
    const char* alias = name == "out" ? "-o, " : name == "quiet" ? "-q, " : "";
    std::string head =
        "  " + std::string(alias) + "--" + name + (s.value_name.empty() ? "" : " " + s.value_name);
    out << head << std::string(head.size() < 30 ? 30 - head.size() : 1, ' ') << s.help;
    if (!s.fallback.empty()) out << " (default " << s.fallback << ")";
    out << "\n";
  }
  out << "  --help                      this text\n";
  return out.str();
}

bool Options::flag(const std::string& name) const { return values_.count(name) > 0; }

std::string Options::text(const std::string& name) const {
  const auto it = values_.find(name);
  return it != values_.end() ? it->second : specs_.at(name).fallback;
}

std::string Options::required(const std::string& name) const {
  const std::string v = text(name);
  if (v.empty()) throw UsageError("option --" + name + " is required");
  return v;
}

void Options::bad(const std::string& name, const std::string& value, const std::string& why) const {
  throw UsageError("--" + name + ": '" + value + "' " + why);
}

double Options::real(const std::string& name, double min, double max) const {
  const std::string t = text(name);
  const double v = parse_real("--" + name, t);
  if (v < min || v > max) {
    std::ostringstream range;
    range << "is outside [" << min << ", " << max << "]";
    bad(name, t, range.str());
  }
  return v;
}

long long Options::integer(const std::string& name, long long min, long long max) const {
  const std::string t = text(name);
  const long long v = parse_integer("--" + name, t);
  if (v < min || v > max) {
    bad(name, t, "is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  }
  return v;
}

std::uint64_t Options::seed(const std::string& name) const {
  const std::string t = text(name);
  const auto v = parse_unsigned_token(t);
  if (!v) bad(name, t, "is not an unsigned 64-bit integer");
  return *v;
}

std::vector<std::string> Options::list(const std::string& name) const {
  const std::string t = text(name);
  std::vector<std::string> items;
  std::stringstream in(t);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty()) bad(name, t, "has an empty item");
    items.push_back(item);
  }
  if (!t.empty() && t.back() == ',') bad(name, t, "has an empty item");
  if (items.empty()) bad(name, t, "is empty");
  return items;
}

std::vector<double> parse_range(const std::string& option, const std::string& text, double min,
                                double max) {
  std::vector<double> values;
  auto in_bounds = [&](double v, const std::string& item) {
    if (v < min || v > max) {
      std::ostringstream msg;
      msg << option << ": " << item << " is outside [" << min << ", " << max << "]";
      throw UsageError(msg.str());
    }
    return v;
  };
  auto round10 = [](double v) { return std::round(v * 1e10) / 1e10; };
  if (text.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, ':')) parts.push_back(part);
    if (parts.size() != 3) throw UsageError(option + ": '" + text + "' is not start:stop:step");
    const double start = in_bounds(parse_real(option + " start", parts[0]), parts[0]);
    const double stop = in_bounds(parse_real(option + " stop", parts[1]), parts[1]);
    const double step = parse_real(option + " step", parts[2]);
    if (!(step > 0.0)) throw UsageError(option + ": step '" + parts[2] + "' must be > 0");
    if (stop < start)
      throw UsageError(option + ": stop " + parts[1] + " is below start " + parts[0]);
    for (long k = 0;; ++k) {
      const double v = round10(start + double(k) * step);
      if (v >= stop - 1e-9) break;
      values.push_back(v);
      if (values.size() > 100000) throw UsageError(option + ": '" + text + "' has too many points");
    }
    values.push_back(stop);  // the stop value is always a point of the sweep
    return values;
  }
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) values.push_back(in_bounds(parse_real(option, item), item));
  if (values.empty()) throw UsageError(option + ": no values");
  return values;
}

}  // namespace verifybench
