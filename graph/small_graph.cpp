#include "graph/small_graph.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/detail/multiversion.hpp"
#include "graph/compatibility_graph.hpp"

namespace verifybench {

namespace {

using Word = std::uint64_t;

inline int lowest(Word x) { return __builtin_ctzll(x); }
inline Word bit(int v) { return Word{1} << v; }

/// Extends a clique of `size` by vertices of `candidates`; `best` is the largest found so far.
void expand(const SmallGraph& g, Word candidates, int size, int& best) {
  // Greedy colouring in vertex order: a colour class is an independent set, so a clique takes at
  // most one vertex of each class, and the i-th vertex in colour order extends by <= colour[i].
  int order[SmallGraph::kMaxVertices], colour[SmallGraph::kMaxVertices], m = 0;
  for (Word uncoloured = candidates, k = 1; uncoloured; ++k) {
    for (Word q = uncoloured; q;) {
      const int v = lowest(q);
      q &= ~g.row[v] & ~bit(v);
      uncoloured &= ~bit(v);
      order[m] = v;
      colour[m++] = static_cast<int>(k);
    }
  }
  for (int i = m - 1; i >= 0; --i) {
    if (size + colour[i] <= best) return;
    const int v = order[i];
    const Word next = candidates & g.row[v];
    if (next) {
      expand(g, next, size + 1, best);
    } else if (size + 1 > best) {
      best = size + 1;
    }
    candidates &= ~bit(v);
  }
}

/// Eq. (1)'s gaps | ||m_b - m_a|| - ||q_b - q_a|| | of one row, b in [0, count): structure of
/// arrays (m_x, m_y, (m_z,) q_x, q_y, (q_z)) so that the loop vectorises; compiled for AVX-512, AVX2
/// and baseline x86-64. Contracted multiply-adds may round differently from the definition, so
/// gaps within a band of eps are decided again by `compatible`.
template <int Dim>
VB_MULTIVERSION void row_gaps(const double (*c)[SmallGraph::kMaxVertices], int a, int count,
                              double* gap) {
  for (int b = 0; b < count; ++b) {
    double ls = 0.0, lt = 0.0;
    for (int d = 0; d < Dim; ++d) {
      const double u = c[d][b] - c[d][a], v = c[Dim + d][b] - c[Dim + d][a];
      ls += u * u;
      lt += v * v;
    }
    gap[b] = std::fabs(std::sqrt(ls) - std::sqrt(lt));
  }
}

}  // namespace

template <int Dim>
SmallGraph small_compatibility_graph(const Correspondences<Dim>& corr, const int* index, int count,
                                     double eps) {
  if (count < 0 || count > SmallGraph::kMaxVertices) {
    throw std::invalid_argument("small_compatibility_graph: " + std::to_string(count) +
                                " vertices; at most 64");
  }
  SmallGraph g;
  g.n = count;
  double c[2 * Dim][SmallGraph::kMaxVertices];
  double extent = 0.0;
  for (int k = 0; k < count; ++k) {
    for (int d = 0; d < Dim; ++d) {
      c[d][k] = corr.source(d, index[k]);
      c[Dim + d][k] = corr.target(d, index[k]);
      extent = std::max({extent, std::abs(c[d][k]), std::abs(c[Dim + d][k])});
    }
  }
  // Rounding of the vector kernel's gap is a few ulp of the coordinates; 1e-12 of the extent
  // leaves a wide margin and is still far below any eps in use.
  const double band = 1e-12 * (extent + eps);
  double gap[SmallGraph::kMaxVertices];
  for (int a = 0; a + 1 < count; ++a) {
    row_gaps<Dim>(c, a, count, gap);
    for (int b = a + 1; b < count; ++b) {
      const bool edge = std::fabs(gap[b] - eps) <= band ? compatible(corr, index[a], index[b], eps)
                                                         : gap[b] < eps;
      if (edge) {
        g.row[a] |= bit(b);
        g.row[b] |= bit(a);
      }
    }
  }
  return g;
}

int small_clique_number(const SmallGraph& g) {
  int best = 0;
  const Word all = g.n == 64 ? ~Word{0} : bit(g.n) - 1;
  if (all) expand(g, all, 0, best);
  return best;
}

template SmallGraph small_compatibility_graph<2>(const Correspondences<2>&, const int*, int, double);
template SmallGraph small_compatibility_graph<3>(const Correspondences<3>&, const int*, int, double);

}  // namespace verifybench
