// `verifybench list`: every registered solver, generator kind and clique algorithm of this build.
#include <cstdio>

#include "apps/cli.hpp"
#include "cliques/max_clique.hpp"
#include "generators/synthetic.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

int cmd_list(const std::vector<std::string>& args) {
  Options o;
  if (o.parse_or_help(args, "usage: verifybench list\n")) return 0;
  std::printf("solvers (sweep, run --solvers):\n");
  for (const auto& info : SolverRegistry::list()) {
    std::printf("  %-18s %s\n", info.name.c_str(), info.description.c_str());
  }
  std::printf("generators (sweep --generator):\n");
  for (const auto& g : list_generators()) {
    std::printf("  %-18s %s%s\n", g.name.c_str(), g.description.c_str(),
                g.supports_3d ? "" : " [2D only]");
  }
  std::printf("clique algorithms (dimacs --algorithms; solver clique-<name>):\n");
  for (const auto& info : CliqueAlgorithms::list()) {
    std::printf("  %-18s %s%s\n", info.name.c_str(), info.description.c_str(),
                info.exact ? "" : " [heuristic]");
  }
  return 0;
}

}  // namespace verifybench
