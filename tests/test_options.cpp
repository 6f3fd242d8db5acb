// The command-line parser bound to fields (apps/options.hpp) and the parameter rows bound through it
// (apps/param_options.hpp): what a line sets, what --help shows, what it refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "apps/options.hpp"
#include "apps/param_options.hpp"
#include "core/param_rows.hpp"

namespace vb = verifybench;

namespace {

struct Toy {
  double eps = 0.1;
  double threshold = 0.0;  ///< eps when not given (a derived default)
  int count = 3;
  bool fast = false;
  std::string mode = "a";
};

std::vector<vb::ParamRow<Toy>> toy_rows() {
  using Row = vb::ParamRow<Toy>;
  std::vector<Row> rows(4);
  rows[0].option = "eps";
  rows[0].key = "eps_m";
  rows[0].value_name = "M";
  rows[0].help = "tolerance";
  rows[0].min = 1e-9;
  rows[0].max = 10.0;
  rows[0].get = [](const Toy& t) { return t.eps; };
  rows[0].set = [](Toy& t, double v) { t.eps = v; };
  rows[1].option = "threshold";
  rows[1].key = "threshold_m";
  rows[1].value_name = "M";
  rows[1].help = "threshold";
  rows[1].min = 0.0;
  rows[1].max = 10.0;
  rows[1].get = [](const Toy& t) { return t.threshold; };
  rows[1].set = [](Toy& t, double v) { t.threshold = v; };
  rows[1].when_absent = [](Toy& t) { t.threshold = t.eps; };
  rows[1].default_note = "eps";
  rows[2].option = "count";
  rows[2].key = "count";
  rows[2].value_name = "K";
  rows[2].help = "count";
  rows[2].kind = Row::Kind::integer;
  rows[2].min = 1;
  rows[2].max = 100;
  rows[2].get = [](const Toy& t) { return t.count; };
  rows[2].set = [](Toy& t, double v) { t.count = static_cast<int>(v); };
  rows[3].option = "fast";
  rows[3].key = "fast";
  rows[3].help = "fast";
  rows[3].kind = Row::Kind::flag;
  rows[3].get = [](const Toy& t) { return t.fast ? 1.0 : 0.0; };
  rows[3].set = [](Toy& t, double v) { t.fast = v != 0.0; };
  return rows;
}

/// The UsageError's message of parsing `args` into fresh fields, "" when it parses.
std::string refusal(const std::vector<std::string>& args) {
  Toy toy;
  std::vector<std::string> names{"x"}, files;
  std::uint64_t seed = 1;
  vb::Options o;
  vb::cli::add_rows(o, toy_rows(), toy);
  o.list("names", names, "A,B", "names").seed("seed", seed, "seed").allow_positional("F", files);
  try {
    o.parse(args);
  } catch (const vb::UsageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Options, AGivenValueIsWrittenIntoItsFieldAndTheOthersKeepTheirs) {
  Toy toy;
  toy.count = 7;  // a command's own default
  std::vector<std::string> names{"x"}, files;
  std::uint64_t seed = 1;
  vb::Options o;
  vb::cli::add_rows(o, toy_rows(), toy);
  o.list("names", names, "A,B", "names").seed("seed", seed, "seed").allow_positional("F", files);
  o.parse({"--eps=0.25", "--fast", "a.clq", "--names", "p,q", "--seed", "18446744073709551615",
           "b.clq"});
  EXPECT_DOUBLE_EQ(toy.eps, 0.25);
  EXPECT_DOUBLE_EQ(toy.threshold, 0.25);  // derived from the given eps after it was set
  EXPECT_EQ(toy.count, 7);
  EXPECT_TRUE(toy.fast);
  EXPECT_EQ(names, (std::vector<std::string>{"p", "q"}));
  EXPECT_EQ(seed, 18446744073709551615ULL);
  EXPECT_EQ(files, (std::vector<std::string>{"a.clq", "b.clq"}));
  EXPECT_TRUE(o.given("eps"));
  EXPECT_FALSE(o.given("count"));
  EXPECT_THROW(o.require("count"), vb::UsageError);
}

TEST(Options, ADerivedDefaultIsNotAppliedOverAGivenValue) {
  Toy toy;
  vb::Options o;
  vb::cli::add_rows(o, toy_rows(), toy);
  o.parse({"--threshold", "2", "--eps", "0.5"});
  EXPECT_DOUBLE_EQ(toy.threshold, 2.0);
  EXPECT_DOUBLE_EQ(toy.eps, 0.5);
}

TEST(Options, HelpShowsEachFieldsValueAtDeclarationAndTheRowsRange) {
  Toy toy;
  toy.eps = 0.3;
  toy.count = 12;
  vb::Options o;
  vb::cli::add_rows(o, toy_rows(), toy);
  const std::string help = o.help();
  EXPECT_NE(help.find("--eps M"), std::string::npos) << help;
  EXPECT_NE(help.find("tolerance, in [1e-09, 10] (default 0.3)"), std::string::npos) << help;
  EXPECT_NE(help.find("(default eps)"), std::string::npos) << help;
  EXPECT_NE(help.find("count, in [1, 100] (default 12)"), std::string::npos) << help;
  EXPECT_EQ(help.find("fast (default"), std::string::npos) << help;  // a flag shows no default
}

TEST(Options, ARequiredOptionGivenEmptyIsMissingAndHelpSetsNothing) {
  std::string out = "unchanged";
  Toy toy;
  vb::Options o;
  vb::cli::add_rows(o, toy_rows(), toy);
  o.text("out", out, "FILE", "report");
  o.parse({"--out", ""});
  EXPECT_TRUE(o.given("out"));
  EXPECT_THROW(o.require("out"), vb::UsageError);
  // --help prints the options whatever the other values are: a bad one is not refused, none is set.
  Toy other;
  vb::Options h;
  vb::cli::add_rows(h, toy_rows(), other);
  EXPECT_NO_THROW(h.parse({"--eps", "nan", "--count", "7", "--help"}));
  EXPECT_EQ(other.count, 3);
  EXPECT_DOUBLE_EQ(other.eps, 0.1);
}

TEST(Options, RefusesWithTheOptionAndTheValueNamed) {
  EXPECT_EQ(refusal({"--eps", "11"}), "--eps: '11' is outside [1e-09, 10]");
  EXPECT_EQ(refusal({"--eps", "nan"}), "--eps: 'nan' is not a finite number");
  EXPECT_EQ(refusal({"--eps", "1e999"}), "--eps: '1e999' is not a finite number");
  EXPECT_EQ(refusal({"--eps", "0.1x"}), "--eps: '0.1x' is not a finite number");
  EXPECT_EQ(refusal({"--count", "2.5"}), "--count: '2.5' is not an integer");
  EXPECT_EQ(refusal({"--count", "0"}), "--count: '0' is outside [1, 100]");
  EXPECT_EQ(refusal({"--seed", "-1"}), "--seed: '-1' is not an unsigned 64-bit integer");
  EXPECT_EQ(refusal({"--names", "a,,b"}), "--names: 'a,,b' has an empty item");
  EXPECT_EQ(refusal({"--fast=1"}), "option --fast takes no value");
  EXPECT_EQ(refusal({"--count", "2", "--count", "3"}), "option --count given twice");
  EXPECT_EQ(refusal({"--count"}), "option --count needs a value");
  EXPECT_EQ(refusal({"--cuont", "2"}), "unknown option '--cuont' (did you mean --count?; see --help)");
  EXPECT_EQ(refusal({"--eps", "0.5", "--count", "4"}), "");
}
