#include "graph/bitgraph.hpp"

#include <algorithm>

#include "core/detail/multiversion.hpp"

namespace verifybench {

BitGraph::BitGraph(int n)
    : n_(n),
      words_((n + kWordBits - 1) / kWordBits),
      bits_(static_cast<std::size_t>(n) * static_cast<std::size_t>(words_)) {}

std::size_t BitGraph::bytes_for(std::size_t n) {
  return n * ((n + kWordBits - 1) / kWordBits) * sizeof(Word);
}

namespace {
// Baseline x86-64 has no popcnt instruction; pick it (and wider vectors) at load time where
// present.
VB_MULTIVERSION_POPCNT
int count_bits(const BitGraph::Word* bits, int words) {
  int d = 0;
  for (int w = 0; w < words; ++w) d += __builtin_popcountll(bits[w]);
  return d;
}
}  // namespace

int BitGraph::degree(int v) const { return count_bits(row(v), words_); }

int BitGraph::count(const Word* bits, int words) { return count_bits(bits, words); }

void BitGraph::transpose_block(Word* a) {
  Word m = 0x00000000FFFFFFFFull;
  for (int j = 32; j; j >>= 1, m ^= m << j) {  // swap ever smaller off-diagonal sub-blocks
    for (int k = 0; k < 64; k = ((k | j) + 1) & ~j) {
      const Word t = ((a[k] >> j) ^ a[k | j]) & m;
      a[k | j] ^= t;
      a[k] ^= t << j;
    }
  }
}

long long BitGraph::edge_count() const {
  long long total = 0;
  for (int v = 0; v < n_; ++v) total += degree(v);
  return total / 2;
}

bool BitGraph::is_clique(const std::vector<int>& vertices) const {
  for (std::size_t a = 0; a < vertices.size(); ++a) {
    for (std::size_t b = a + 1; b < vertices.size(); ++b) {
      if (vertices[a] == vertices[b] || !adjacent(vertices[a], vertices[b])) return false;
    }
  }
  return true;
}

}  // namespace verifybench
