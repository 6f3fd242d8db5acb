#pragma once
// Graphs of at most 64 vertices, one word per adjacency row: the parts of the screen's coarse
// score bounds (clique_number_bound), built and solved without a heap allocation.
#include <cstdint>

#include "core/correspondences.hpp"

namespace verifybench {

struct SmallGraph {
  static constexpr int kMaxVertices = 64;
  int n = 0;
  std::uint64_t row[kMaxVertices] = {};  ///< bit u of row[v]: {u, v} is an edge
};

/// The Eq. (1) graph at `eps` of the correspondences index[0..count), vertex k for index[k], in
/// double precision (the definition build_compatibility_graph reproduces). count <= 64.
template <int Dim>
SmallGraph small_compatibility_graph(const Correspondences<Dim>& corr, const int* index, int count,
                                     double eps);

/// The exact clique number: branch and bound with greedy colouring bounds (Tomita's MCQ, on one
/// word). Summed over parts of 64 of the corpus' null sets it is 8-29% below the sum of max
/// core + 1, the bound core_decomposition gives (BENCHMARK.md section 24).
int small_clique_number(const SmallGraph& g);

}  // namespace verifybench
