#pragma once
// The result of a clique peer run in a killable child: no clique (status time_limit) when it was
// stopped, else its clique, proven maximum.
#include <algorithm>
#include <optional>
#include <vector>

#include "cliques/max_clique.hpp"

namespace verifybench::detail {

inline CliqueSearchResult peer_result(std::optional<std::vector<int>> clique, int n) {
  CliqueSearchResult r;
  r.stopped = !clique.has_value();
  r.optimal = !r.stopped;
  if (clique) {
    r.clique = std::move(*clique);
    std::sort(r.clique.begin(), r.clique.end());
  }
  r.upper_bound = r.optimal ? static_cast<int>(r.clique.size()) : n;
  return r;
}

}  // namespace verifybench::detail
