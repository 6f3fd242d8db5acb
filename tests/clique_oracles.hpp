#pragma once
// auto against the exact oracles on graphs too large for the brute force: plain BBMC (itself
// checked against the brute force in test_max_clique) and cliquer where it is built.
#include <gtest/gtest.h>

#include <string>

#include "cliques/max_clique.hpp"
#include "graph/bitgraph.hpp"

namespace verifybench::test {

/// Runs auto on g and checks its clique against BBMC's and cliquer's; auto's result in *out.
inline void expect_auto_matches_oracles(const BitGraph& g, const std::string& what,
                                        CliqueSearchResult* out = nullptr) {
  register_clique_algorithms();
  const auto r = CliqueAlgorithms::get("auto").run(g, {});
  const auto oracle = CliqueAlgorithms::get("bbmc").run(g, {});
  ASSERT_TRUE(r.optimal && oracle.optimal) << what;
  ASSERT_TRUE(g.is_clique(r.clique)) << what;
  ASSERT_EQ(r.clique.size(), oracle.clique.size()) << what;
  if (VB_BUILT_CLIQUER) {
    ASSERT_EQ(r.clique.size(), CliqueAlgorithms::get("cliquer").run(g, {}).clique.size()) << what;
  }
  if (out) *out = r;
}

}  // namespace verifybench::test
