#include "apps/options.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
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

Options& Options::bind(const std::string& name, const std::string& value_name,
                       const std::string& shown, const std::string& help, Set set,
                       std::function<void()> absent) {
  order_.push_back(name);
  specs_[name] = {value_name, shown, help, std::move(set), nullptr, std::move(absent)};
  return *this;
}

Options& Options::flag(const std::string& name, const std::string& help,
                       std::function<void()> on, std::function<void()> absent) {
  order_.push_back(name);
  specs_[name] = {"", "", help, nullptr, std::move(on), std::move(absent)};
  return *this;
}

Options& Options::real(const std::string& name, double& field, const std::string& value_name,
                       const std::string& help, double min, double max) {
  return bind(name, value_name, shown_number(field), help,
              [&field, name, min, max](const std::string& v) {
                field = real_value(name, v, min, max);
              });
}

Options& Options::seed(const std::string& name, std::uint64_t& field, const std::string& help) {
  return bind(name, "S", std::to_string(field), help, [&field, name](const std::string& v) {
    const auto value = parse_unsigned_token(v);
    if (!value) throw UsageError("--" + name + ": '" + v + "' is not an unsigned 64-bit integer");
    field = *value;
  });
}

Options& Options::text(const std::string& name, std::string& field, const std::string& value_name,
                       const std::string& help) {
  return bind(name, value_name, field, help, [&field](const std::string& v) { field = v; });
}

Options& Options::list(const std::string& name, std::vector<std::string>& field,
                       const std::string& value_name, const std::string& help) {
  std::string shown;
  for (const auto& item : field) shown += (shown.empty() ? "" : ",") + item;
  return bind(name, value_name, shown, help,
              [&field, name](const std::string& v) { field = list_value(name, v); });
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
  // --help prints the options whatever the others' values: no setter runs then.
  const bool help_asked = std::find(args.begin(), args.end(), "--help") != args.end() ||
                          std::find(args.begin(), args.end(), "-h") != args.end();
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
    if (!spec->second.set && arg.find('=') != std::string::npos) {
      throw UsageError("option --" + name + " takes no value");
    }
  }
  // Each option's setter is CLI11's callback: it runs once parsing is done, in declaration order.
  CLI::App app;
  app.set_help_flag();  // --help is ours: it prints the grouped help below
  app.add_flag("-h,--help", help_);
  for (const auto& name : order_) {
    if (name[0] == '\n') continue;
    const Spec& spec = specs_.at(name);
    if (spec.set) {
      app.add_option_function<std::string>("--" + name,
                                            [this, name, help_asked, &spec](const std::string& v) {
                                              if (v.empty()) empty_.insert(name);
                                              if (!help_asked) spec.set(v);
                                            })
          ->allow_extra_args(false);
    } else {
      app.add_flag_callback("--" + name, [help_asked, &spec] {
        if (!help_asked) spec.on();
      });
    }
  }
  if (positional_) app.add_option(positional_name_, *positional_);
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
  for (const auto& [name, count] : seen) given_.insert(name);
  if (help_) return;
  for (const auto& name : order_) {
    if (name[0] == '\n' || given(name)) continue;
    const Spec& spec = specs_.at(name);
    if (spec.absent) spec.absent();
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
    if (!s.shown.empty()) out << " (default " << s.shown << ")";
    out << "\n";
  }
  out << "  --help                      this text\n";
  return out.str();
}

void Options::require(const std::string& name) const {
  if (!given(name) || empty_.count(name)) throw UsageError("option --" + name + " is required");
}

double Options::real_value(const std::string& name, const std::string& text, double min,
                           double max) {
  const double v = parse_real("--" + name, text);
  if (v < min || v > max) {
    std::ostringstream range;
    range << "--" << name << ": '" << text << "' is outside [" << min << ", " << max << "]";
    throw UsageError(range.str());
  }
  return v;
}

long long Options::integer_value(const std::string& name, const std::string& text, long long min,
                                 long long max) {
  const long long v = parse_integer("--" + name, text);
  if (v < min || v > max) {
    throw UsageError("--" + name + ": '" + text + "' is outside [" + std::to_string(min) + ", " +
                     std::to_string(max) + "]");
  }
  return v;
}

std::vector<std::string> Options::list_value(const std::string& name, const std::string& text) {
  const auto bad = [&](const std::string& why) {
    throw UsageError("--" + name + ": '" + text + "' " + why);
  };
  std::vector<std::string> items;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty()) bad("has an empty item");
    items.push_back(item);
  }
  if (!text.empty() && text.back() == ',') bad("has an empty item");
  if (items.empty()) bad("is empty");
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
