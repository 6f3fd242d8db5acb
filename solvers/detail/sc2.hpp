#pragma once
// The second order spatial compatibility of SC2-PCR (Chen, Sun, Yang, Tao, CVPR 2022), read off
// the hard first-order compatibility graph. With d_ij = | ||m_i - m_j|| - ||q_i - q_j|| | and the
// hard measure C_ij = [d_ij < d_thr] (Eqs. 4-6; C_ii = 1, as d_ii = 0), which is the graph of
// Eq. (1) at eps = d_thr plus the diagonal, the second order measure is
//   SC2 = C (.) (C x C),  SC2_ij = C_ij sum_k C_ik C_kj                               (Eq. 7):
// for i != j adjacent, the common neighbours of i and j plus 2 (k = i and k = j), for i = j the
// degree plus 1, and 0 elsewhere. A row costs n popcounts of n / 64 words and no n x n matrix.
#include <vector>

#include "core/detail/multiversion.hpp"
#include "graph/bitgraph.hpp"

namespace verifybench {

/// |a & b| over `words` words (the common neighbours of two rows), compiled with the hardware
/// popcount where the CPU has one: baseline x86-64 has none, and a software count made sc2-pcr,
/// turboreg and fastmac 2-3x slower. Shared by the three.
VB_MULTIVERSION_POPCNT
static int common_count(const BitGraph::Word* a, const BitGraph::Word* b, int words) {
  int common = 0;
  for (int w = 0; w < words; ++w) common += __builtin_popcountll(a[w] & b[w]);
  return common;
}

/// SC2_ij of Eq. (7) on the graph `c` of C without its diagonal.
inline int sc2_entry(const BitGraph& c, int i, int j) {
  if (i == j) return c.degree(i) + 1;
  if (!c.adjacent(i, j)) return 0;
  return common_count(c.row(i), c.row(j), c.words()) + 2;
}

/// Row i of SC2: row[j] = SC2_ij for every j.
inline void sc2_row(const BitGraph& c, int i, std::vector<int>& row) {
  row.assign(static_cast<std::size_t>(c.size()), 0);
  for (int j = 0; j < c.size(); ++j) row[static_cast<std::size_t>(j)] = sc2_entry(c, i, j);
}

}  // namespace verifybench
