// Core decomposition, the greedy lower bound and the exact clique algorithms of max_clique.hpp.
#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>

#include "solvers/bbmc.hpp"
#include "solvers/max_clique.hpp"

namespace verifybench {

using detail::BranchAndBound;
using detail::for_each_bit;
using detail::kBits;
using detail::SearchBudget;
using detail::Word;

std::vector<int> greedy_clique(const BitGraph& g, const CoreDecomposition& cd) {
  const int W = g.words();
  std::vector<int> best, clique;
  std::vector<Word> cand(static_cast<std::size_t>(W));
  for (auto it = cd.order.rbegin(); it != cd.order.rend(); ++it) {
    const int v = *it;
    if (cd.core[v] + 1 <= static_cast<int>(best.size())) continue;
    clique.assign(1, v);
    std::copy(g.row(v), g.row(v) + W, cand.begin());
    for (;;) {
      int pick = -1;
      for_each_bit(cand.data(), W, [&](int u) {
        if (pick < 0 || cd.core[u] > cd.core[pick]) pick = u;
      });
      if (pick < 0) break;
      clique.push_back(pick);
      const Word* row = g.row(pick);
      for (int w = 0; w < W; ++w) cand[w] &= row[w];
    }
    if (clique.size() > best.size()) best = clique;
  }
  return best;
}

CoreDecomposition core_decomposition(const BitGraph& g) {
  const int n = g.size();
  CoreDecomposition cd;
  std::vector<int> deg(static_cast<std::size_t>(n)), pos(static_cast<std::size_t>(n)),
      vert(static_cast<std::size_t>(n));
  int max_deg = 0;
  for (int v = 0; v < n; ++v) max_deg = std::max(max_deg, deg[v] = g.degree(v));
  std::vector<int> bin(static_cast<std::size_t>(max_deg) + 1, 0);
  for (int v = 0; v < n; ++v) ++bin[deg[v]];
  for (int d = 0, start = 0; d <= max_deg; ++d) {
    const int c = bin[d];
    bin[d] = start;
    start += c;
  }
  for (int v = 0; v < n; ++v) {
    pos[v] = bin[deg[v]]++;
    vert[pos[v]] = v;
  }
  for (int d = max_deg; d > 0; --d) bin[d] = bin[d - 1];
  if (max_deg >= 0 && !bin.empty()) bin[0] = 0;
  for (int i = 0; i < n; ++i) {
    const int v = vert[i];
    for_each_bit(g.row(v), g.words(), [&](int u) {
      if (deg[u] > deg[v]) {
        const int du = deg[u], pu = pos[u], pw = bin[du], w = vert[pw];
        if (u != w) {
          std::swap(vert[pu], vert[pw]);
          pos[u] = pw;
          pos[w] = pu;
        }
        ++bin[du];
        --deg[u];
      }
    });
  }
  cd.core = std::move(deg);
  cd.order = std::move(vert);
  return cd;
}


namespace {

SearchBudget make_budget(const CliqueSearchParams& p) {
  SearchBudget b;
  b.deadline = deadline_after(p.time_limit_s);
  b.node_limit = p.node_limit;
  return b;
}

int max_core(const CoreDecomposition& cd) {
  return cd.core.empty() ? -1 : *std::max_element(cd.core.begin(), cd.core.end());
}

/// BBMC on the subgraph induced by `vertices` (in that order, which is the initial colouring
/// order); returns a clique larger than `incumbent` in original ids, or an empty vector.
std::vector<int> search_ordered(const BitGraph& g, const std::vector<int>& vertices, int incumbent,
                                SearchBudget& budget, bool recolour = false) {
  const BitGraph sub = detail::permuted(g, vertices);
  BranchAndBound bb(sub, incumbent, budget, recolour);
  bb.run();
  std::vector<int> found;
  for (int k : bb.best()) found.push_back(vertices[static_cast<std::size_t>(k)]);
  return found;
}

CliqueSearchResult finish(std::vector<int> clique, bool exact, const SearchBudget& budget, int upper) {
  CliqueSearchResult r;
  std::sort(clique.begin(), clique.end());
  r.clique = std::move(clique);
  r.stopped = budget.stopped;
  r.nodes = budget.nodes;
  r.upper_bound = upper;
  r.optimal = (exact && !budget.stopped) || static_cast<int>(r.clique.size()) == upper;
  return r;
}

// bbmc / bbmcr: the whole graph in min-width order (highest core first), no pre-pruning.
template <bool kRecolour>
CliqueSearchResult run_bbmc(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = make_budget(p);
  const CoreDecomposition cd = core_decomposition(g);
  const std::vector<int> order(cd.order.rbegin(), cd.order.rend());
  return finish(search_ordered(g, order, 0, budget, kRecolour), true, budget, max_core(cd) + 1);
}

// bbmc-kcore: greedy lower bound, drop vertices whose core number cannot beat it, BBMC on the rest.
CliqueSearchResult run_bbmc_kcore(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = make_budget(p);
  const CoreDecomposition cd = core_decomposition(g);
  const int upper = max_core(cd) + 1;
  std::vector<int> best = greedy_clique(g, cd);
  const int incumbent = static_cast<int>(best.size());
  if (incumbent < upper) {
    std::vector<int> kept;  // a clique larger than the incumbent lies in the incumbent-core
    for (auto it = cd.order.rbegin(); it != cd.order.rend(); ++it) {
      if (cd.core[static_cast<std::size_t>(*it)] >= incumbent) kept.push_back(*it);
    }
    std::vector<int> found = search_ordered(g, kept, incumbent, budget);
    if (!found.empty()) best = std::move(found);
  }
  return finish(std::move(best), true, budget, upper);
}

// bbmc-dec: every maximum clique has a first vertex v in degeneracy order, and its other vertices
// are later neighbours of v: at most degeneracy of them. Solving each such neighbourhood as a small
// compact BBMC problem, highest core first, is what PMC does (with a weaker bound inside).
CliqueSearchResult run_bbmc_dec(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = make_budget(p);
  const int n = g.size();
  const CoreDecomposition cd = core_decomposition(g);
  const int upper = max_core(cd) + 1;
  std::vector<int> best = greedy_clique(g, cd);
  // Relabel in min-width order (0 = removed last): v's later neighbours are then the smaller ids.
  const std::vector<int> order(cd.order.rbegin(), cd.order.rend());
  const BitGraph h = detail::permuted(g, order);
  std::vector<Word> mask(static_cast<std::size_t>(h.words()), 0);
  std::vector<int> members;
  for (int v = 0; v < n && static_cast<int>(best.size()) < upper; ++v) {
    const int size = static_cast<int>(best.size());
    if (cd.core[static_cast<std::size_t>(order[static_cast<std::size_t>(v)])] + 1 <= size) continue;
    members.clear();
    const Word* row = h.row(v);
    for (int w = 0; w <= v / kBits; ++w) {
      for (Word x = row[w]; x; x &= x - 1) {
        const int u = w * kBits + detail::lowest_bit(x);
        if (u >= v) break;
        if (cd.core[static_cast<std::size_t>(order[static_cast<std::size_t>(u)])] >= size) members.push_back(u);
      }
    }
    if (static_cast<int>(members.size()) + 1 <= size) continue;
    const BitGraph sub = BranchAndBound::induced(h, members, mask);
    BranchAndBound bb(sub, size - 1, budget);
    bb.run();
    if (!bb.best().empty()) {
      best.assign(1, order[static_cast<std::size_t>(v)]);
      for (int k : bb.best()) best.push_back(order[static_cast<std::size_t>(members[static_cast<std::size_t>(k)])]);
    }
    if (budget.stopped) break;
  }
  return finish(std::move(best), true, budget, upper);
}

CliqueSearchResult run_greedy(const BitGraph& g, const CliqueSearchParams& p) {
  const SearchBudget budget = make_budget(p);
  const CoreDecomposition cd = core_decomposition(g);
  return finish(greedy_clique(g, cd), false, budget, max_core(cd) + 1);
}

std::map<std::string, CliqueAlgorithmInfo>& algorithms() {
  static std::map<std::string, CliqueAlgorithmInfo> table;
  return table;
}

}  // namespace

void CliqueAlgorithms::add(CliqueAlgorithmInfo info) {
  const std::string name = info.name;
  if (!algorithms().emplace(name, std::move(info)).second) {
    throw std::logic_error("clique algorithm '" + name + "' is registered twice");
  }
}

const CliqueAlgorithmInfo& CliqueAlgorithms::get(const std::string& name) {
  const auto it = algorithms().find(name);
  if (it == algorithms().end()) {
    std::string known;
    for (const auto& entry : algorithms()) known += (known.empty() ? "" : ", ") + entry.first;
    throw std::invalid_argument("unknown clique algorithm '" + name + "' (known: " + known + ")");
  }
  return it->second;
}

std::vector<CliqueAlgorithmInfo> CliqueAlgorithms::list() {
  std::vector<CliqueAlgorithmInfo> out;
  for (const auto& entry : algorithms()) out.push_back(entry.second);
  return out;
}

void register_clique_peers();  // clique_peers.cpp: cliquer, igraph

void register_clique_algorithms() {
  static std::once_flag once;
  std::call_once(once, [] {
    CliqueAlgorithms::add({"bbmc", "BBMC: bitset branch and bound, greedy colouring bound, min-width order",
                           true, run_bbmc<false>});
    CliqueAlgorithms::add({"bbmcr", "BBMCR: BBMC with re-colouring (MCS Re-NUMBER) of branching candidates",
                           true, run_bbmc<true>});
    CliqueAlgorithms::add({"bbmc-kcore", "BBMC after a greedy lower bound and k-core pruning (TEASER++/PMC-style pre-pruning)",
                           true, run_bbmc_kcore});
    CliqueAlgorithms::add({"bbmc-dec", "BBMC on each vertex's later neighbours in degeneracy order (PMC-style decomposition)",
                           true, run_bbmc_dec});
    CliqueAlgorithms::add({"greedy", "greedy clique by core number: a heuristic, no optimality proof",
                           false, run_greedy});
    register_clique_peers();
  });
}

CliqueSearchResult max_clique(const BitGraph& g, const CliqueSearchParams& params) {
  register_clique_algorithms();
  return CliqueAlgorithms::get(kDefaultCliqueAlgorithm).run(g, params);
}

}  // namespace verifybench
