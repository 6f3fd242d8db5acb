// verifybench: command-line front end; see `verifybench --help`. One file per command (cmd_*.cpp).
// Exit codes, one per failure class (README, "Exit codes"): 0 done; 1 done, but rows have status
// error (the report is written and says why); 2 refused before any work (bad command line, unknown
// name, malformed or unreadable input, an output that cannot or may not be written); 3 failed
// during the work (a write that failed, out of memory), leaving nothing half-written.
#include <iostream>

#include "apps/cli.hpp"
#include "harness/builtin.hpp"
#include "verifybench/version.hpp"

namespace vb = verifybench;

namespace {

struct Command {
  const char* name;
  const char* summary;
  int (*run)(const std::vector<std::string>& args, const std::vector<std::string>& argv);
};

const Command kCommands[] = {
    {"list", "registered solvers, generators and clique algorithms",
     [](const auto& args, const auto&) { return vb::cmd_list(args); }},
    {"sweep", "robustness sweep on synthetic sets (success rate and time vs outlier ratio)",
     vb::cmd_sweep},
    {"run", "solvers on a correspondence dump (DIR/dump.json + matches.tsv, or DIR/corr.txt)",
     vb::cmd_run},
    {"dimacs", "maximum clique algorithms on DIMACS graphs (FILE.clq ...)", vb::cmd_dimacs},
    {"graph", "the correspondence graph of Eq. (1) of a dump, as a DIMACS file (for other solvers)",
     vb::cmd_graph},
    {"extract", "a correspondence dump from two scans (ISS + B-SHOT, or BEV + ORB; HBST matching)",
     [](const auto& args, const auto&) { return vb::cmd_extract(args); }},
    {"loop", "loop closure on a sequence: local maps, retrieval, solvers, P/R/F1, pose graph, APE",
     vb::cmd_loop},
    {"merge", "the reports of every shard (--shard I/N) of one command joined into one",
     vb::cmd_merge},
};

std::string usage() {
  std::string text = "usage: verifybench <command> [options]\ncommands:\n";
  for (const Command& c : kCommands) {
    text += "  " + std::string(c.name) + std::string(9 - std::string(c.name).size(), ' ') +
            c.summary + "\n";
  }
  return text +
         "`verifybench <command> --help` lists a command's options; `verifybench --version`.\n";
}

std::string command_names() {
  std::string names;
  for (const Command& c : kCommands) names += (names.empty() ? "" : ", ") + std::string(c.name);
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> all(argv, argv + argc);
  vb::register_builtin_solvers();
  if (argc < 2) {
    std::cerr << "verifybench: error: no command given\n" << usage();
    return 2;
  }
  if (all[1] == "--help" || all[1] == "-h" || all[1] == "help") {
    std::cout << usage();
    return 0;
  }
  if (all[1] == "--version") {
    std::cout << "verifybench " << vb::kVersion << " (commit " << vb::kGitCommit << ", "
              << vb::kBuildType << ")\n";
    return 0;
  }
  const std::vector<std::string> rest(all.begin() + 2, all.end());
  try {
    for (const Command& c : kCommands) {
      if (all[1] == c.name) return c.run(rest, all);
    }
    throw vb::UsageError("unknown command '" + all[1] + "' (commands: " + command_names() + ")");
  } catch (const vb::UsageError& e) {  // bad command line
    std::cerr << "verifybench: error: " << e.what() << "\n";
  } catch (const vb::InputError& e) {  // malformed input file
    std::cerr << "verifybench: error: " << e.what() << "\n";
  } catch (const std::invalid_argument& e) {  // unknown solver, invalid parameter or set
    std::cerr << "verifybench: error: " << e.what() << "\n";
  } catch (const std::exception& e) {  // failed during the work: a write, out of memory, ...
    std::cerr << "verifybench: error: " << e.what() << "\n";
    return 3;
  }
  return 2;
}
