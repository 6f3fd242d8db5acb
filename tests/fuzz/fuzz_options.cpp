// libFuzzer: the command-line parser every command uses (apps/options.cpp): the input's
// NUL-separated words are the arguments of a command that binds one option of each kind.
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
    std::vector<std::string> solvers{"clique", "ransac"}, files;
    double eps = 0.1;
    int trials = 1;
    std::uint64_t seed = 1;
    std::vector<double> outliers;
    bool quiet = false;
    vb::Options o;
    o.list("solvers", solvers, "A,B", "a list")
        .real("eps", eps, "M", "a real", 1e-12, 1e12)
        .integer("trials", trials, "K", "an integer", 1, 1000000)
        .seed("seed", seed, "a seed")
        .bind("outliers", "R", "0.5:0.9:0.1", "a range",
              [&](const std::string& v) { outliers = vb::parse_range("outliers", v, 0.0, 1.0); })
        .flag("quiet", quiet, "a flag")
        .allow_positional("FILE", files);
    o.parse_or_help(args, "usage\n");
  });
  return 0;
}
