// libFuzzer: the command-line parser every command uses (apps/options.cpp): the input's
// NUL-separated words are the arguments of a command that declares one option of each kind.
#include "apps/options.hpp"
#include "fuzz_util.hpp"

namespace vb = verifybench;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      args.emplace_back();
    } else {
      args.back() += static_cast<char>(data[i]);
    }
  }
  vb::fuzz::refuse_or_read([&] {
    vb::Options o;
    o.add("solvers", "A,B", "clique,ransac", "a list")
        .add("eps", "M", "0.1", "a real")
        .add("trials", "K", "1", "an integer")
        .add("seed", "S", "1", "a seed")
        .add("outliers", "R", "0.5:0.9:0.1", "a range")
        .add("quiet", "", "", "a flag")
        .allow_positional("FILE");
    if (o.parse_or_help(args, "usage\n")) return;
    o.list("solvers");
    o.real("eps", 1e-12, 1e12);
    o.integer("trials", 1, 1000000);
    o.seed("seed");
    o.flag("quiet");
    vb::parse_range("outliers", o.text("outliers"), 0.0, 1.0);
  });
  return 0;
}
