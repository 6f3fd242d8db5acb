// Linked into every Google Benchmark binary: the JSON context of each run names the commit the
// build was configured from and the seed of every generated input (SyntheticParams' default, 1),
// so that two saved runs can be told apart and reproduced (scripts/benchmark --compare).
#include <benchmark/benchmark.h>

#include "verifybench/version.hpp"

namespace {

const bool kContext = [] {
  benchmark::AddCustomContext("verifybench_version", verifybench::kVersion);
  benchmark::AddCustomContext("verifybench_commit", verifybench::kGitCommit);
  benchmark::AddCustomContext("verifybench_build_type", verifybench::kBuildType);
  benchmark::AddCustomContext("seed", "1");
  return true;
}();

}  // namespace
