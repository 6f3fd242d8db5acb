#include "core/bitgraph.hpp"

#include <algorithm>


namespace verifybench {

BitGraph::BitGraph(int n)
    : n_(n), words_((n + kWordBits - 1) / kWordBits),
      bits_(static_cast<std::size_t>(n) * static_cast<std::size_t>(words_), 0) {}

std::size_t BitGraph::bytes_for(std::size_t n) {
  return n * ((n + kWordBits - 1) / kWordBits) * sizeof(Word);
}

namespace {
// Baseline x86-64 has no popcnt instruction; pick it (and wider vectors) at load time where present.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v3", "popcnt", "default")))
#endif
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

namespace {

/// out (cols x rows bits, `out_words` words a row) = transpose of in (rows x cols bits).
void transpose(const std::vector<BitGraph::Word>& in, int rows, int in_words, std::vector<BitGraph::Word>& out,
               int cols, int out_words) {
  out.assign(static_cast<std::size_t>(cols) * static_cast<std::size_t>(out_words), 0);
  BitGraph::Word block[64];
  for (int R = 0; R * 64 < rows; ++R) {
    for (int C = 0; C * 64 < cols; ++C) {
      for (int r = 0; r < 64; ++r) {
        const int i = R * 64 + r;
        block[r] = i < rows ? in[static_cast<std::size_t>(i) * in_words + static_cast<std::size_t>(C)] : 0;
      }
      BitGraph::transpose_block(block);
      for (int c = 0; c < 64; ++c) {
        const int j = C * 64 + c;
        if (j < cols) out[static_cast<std::size_t>(j) * out_words + static_cast<std::size_t>(R)] = block[c];
      }
    }
  }
}

}  // namespace

BitGraph BitGraph::select(const std::vector<int>& vertices) const {
  // M[k][l] = A[s_k][s_l]: take rows s_k (B = A[S][:]), transpose (B^T = A[:][S]), take rows s_l
  // again; by symmetry of A that is M itself.
  const int m = static_cast<int>(vertices.size());
  const int mw = (m + kWordBits - 1) / kWordBits;
  std::vector<Word> rows_selected(static_cast<std::size_t>(m) * static_cast<std::size_t>(words_));
  for (int k = 0; k < m; ++k) {
    std::copy(row(vertices[static_cast<std::size_t>(k)]), row(vertices[static_cast<std::size_t>(k)]) + words_,
              rows_selected.begin() + static_cast<std::ptrdiff_t>(k) * words_);
  }
  std::vector<Word> columns;  // n rows of mw words: bit k of row u = A[s_k][u]
  transpose(rows_selected, m, words_, columns, n_, mw);
  BitGraph out(m);
  for (int k = 0; k < m; ++k) {
    const Word* src = columns.data() + static_cast<std::size_t>(vertices[static_cast<std::size_t>(k)]) * mw;
    std::copy(src, src + mw, out.row(k));
  }
  return out;
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
