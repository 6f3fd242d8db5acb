#include "core/bitgraph.hpp"

#include <bitset>

namespace verifybench {

BitGraph::BitGraph(int n)
    : n_(n), words_((n + kWordBits - 1) / kWordBits),
      bits_(static_cast<std::size_t>(n) * static_cast<std::size_t>(words_), 0) {}

std::size_t BitGraph::bytes_for(std::size_t n) {
  return n * ((n + kWordBits - 1) / kWordBits) * sizeof(Word);
}

int BitGraph::degree(int v) const {
  int d = 0;
  const Word* r = row(v);
  for (int w = 0; w < words_; ++w) d += static_cast<int>(std::bitset<kWordBits>(r[w]).count());
  return d;
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
