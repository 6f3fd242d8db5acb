#pragma once
// Undirected graph as bitset adjacency rows: row v has bit u set when {u, v} is an edge.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace verifybench {

class BitGraph {
 public:
  using Word = std::uint64_t;
  static constexpr int kWordBits = 64;

  BitGraph() = default;
  explicit BitGraph(int n);

  /// Bytes the adjacency rows of an n-vertex graph take (to check before building).
  static std::size_t bytes_for(std::size_t n);

  int size() const { return n_; }
  int words() const { return words_; }

  void add_edge(int u, int v) {  // self-loops ignored
    if (u == v) return;
    row(u)[v / kWordBits] |= Word{1} << (v % kWordBits);
    row(v)[u / kWordBits] |= Word{1} << (u % kWordBits);
  }
  bool adjacent(int u, int v) const { return (row(u)[v / kWordBits] >> (v % kWordBits)) & Word{1}; }
  const Word* row(int v) const { return bits_.data() + static_cast<std::size_t>(v) * words_; }
  Word* row(int v) { return bits_.data() + static_cast<std::size_t>(v) * words_; }

  int degree(int v) const;
  /// In-place transpose of a 64x64 bit block: bit c of word r moves to bit r of word c.
  static void transpose_block(Word* block);
  /// Set bits in `words` words (hardware popcount where the CPU has it).
  static int count(const Word* bits, int words);

  long long edge_count() const;
  /// True when every pair of the listed vertices is adjacent.
  bool is_clique(const std::vector<int>& vertices) const;

 private:
  int n_ = 0;
  int words_ = 0;
  std::vector<Word> bits_;
};

}  // namespace verifybench
