// BBMC kernels: the colouring loop (multi-versioned) and induced subgraphs by parallel bit
// extraction: with the members in ascending order, row k of the
// subgraph is the concatenation of pext(row(member k)[w], mask[w]) over the mask's words.
#include <algorithm>
#include <cstring>
#include <numeric>

#include "cliques/detail/bbmc.hpp"
#include "core/detail/multiversion.hpp"

namespace verifybench::detail {

namespace {

/// Software pext: the bits of x at the positions set in m, packed to the bottom.
inline Word soft_pext(Word x, Word m) {
  Word out = 0;
  for (Word bit = 1; m; m &= m - 1, bit <<= 1) {
    if (x & m & (~m + 1)) out |= bit;
  }
  return out;
}

template <bool kHardware>
inline Word pext(Word x, Word m);

template <>
inline Word pext<false>(Word x, Word m) {
  return soft_pext(x, m);
}

#if defined(__x86_64__) && defined(__GNUC__)
template <>
__attribute__((target("bmi2"))) inline Word pext<true>(Word x, Word m) {
  return __builtin_ia32_pext_di(x, m);
}
#endif

struct MaskWord {
  int word;    ///< word index in the big graph
  int offset;  ///< members in earlier words (bit offset in the subgraph row)
  int count;   ///< members in this word
};

template <bool kHardware>
#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("bmi2,popcnt")))
#endif
void fill_rows(const BitGraph& g, const std::vector<int>& vertices, const std::vector<Word>& mask,
               const std::vector<MaskWord>& words, BitGraph& sub) {
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const Word* row = g.row(vertices[k]);
    Word* out = sub.row(static_cast<int>(k));
    // Offsets only grow: gather into a register and store each output word once.
    Word acc = 0;
    int at = 0;
    for (const MaskWord& mw : words) {
      const Word bits = pext<kHardware>(row[mw.word], mask[static_cast<std::size_t>(mw.word)]);
      const int shift = mw.offset % kBits;
      acc |= bits << shift;
      if (shift + mw.count >= kBits) {
        out[at++] = acc;
        acc = shift == 0 ? 0 : bits >> (kBits - shift);
      }
    }
    if (at < sub.words()) out[at] = acc;
  }
}

bool has_bmi2() {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool yes = __builtin_cpu_supports("bmi2");
  return yes;
#else
  return false;
#endif
}

}  // namespace

VB_MULTIVERSION
int colour_kernel(const Word* P, int words, const Word* rows, int kmin, Word* U, Word* Q, int* ord,
                  int* col, int* classes_used, int* coloured, Word* low, int* low_class) {
  // Candidates end at word `end`: no later word of U or Q is ever set, so no loop goes past it
  // (deep in a correspondence graph the candidates fill a few of its 100+ words a row).
  int end = words;
  while (end > 0 && P[end - 1] == 0) --end;
  for (int w = 0; w < end; ++w) U[w] = P[w];
  int k = 0, count = 0, lo = 0, total = 0;
  for (;;) {
    while (lo < end && U[lo] == 0) ++lo;
    if (lo == end) break;
    ++k;
    for (int w = lo; w < end; ++w) Q[w] = U[w];
    for (int w = lo; w < end; ++w) {
      while (Q[w]) {
        const int b = __builtin_ctzll(Q[w]);
        const int v = w * kBits + b;
        U[w] &= ~(Word{1} << b);
        Q[w] &= ~(Word{1} << b);
        const Word* N = rows + static_cast<std::size_t>(v) * static_cast<std::size_t>(words);
        for (int x = w; x < end; ++x) Q[x] &= ~N[x];
        ++total;
        if (k >= kmin) {
          ord[count] = v;
          col[count] = k;
          ++count;
        } else if (low) {
          low[static_cast<std::size_t>(k - 1) * static_cast<std::size_t>(words) +
              static_cast<std::size_t>(w)] |= Word{1} << b;
          if (low_class) low_class[v] = k - 1;
        }
      }
    }
  }
  *classes_used = k;
  *coloured = total;
  return count;
}

BitGraph BranchAndBound::induced(const BitGraph& g, const std::vector<int>& vertices,
                                 std::vector<Word>& mask) {
  std::vector<MaskWord> words;
  for (int v : vertices) {
    const int w = v / kBits;
    if (mask[static_cast<std::size_t>(w)] == 0) words.push_back({w, 0, 0});
    mask[static_cast<std::size_t>(w)] |= Word{1} << (v % kBits);
  }
  int offset = 0;
  for (MaskWord& mw : words) {
    mw.offset = offset;
    mw.count = __builtin_popcountll(mask[static_cast<std::size_t>(mw.word)]);
    offset += mw.count;
  }
  BitGraph sub(static_cast<int>(vertices.size()));
  if (has_bmi2()) {
    fill_rows<true>(g, vertices, mask, words, sub);
  } else {
    fill_rows<false>(g, vertices, mask, words, sub);
  }
  for (const MaskWord& mw : words) mask[static_cast<std::size_t>(mw.word)] = 0;
  return sub;
}

// Relabelling scatters one bit per edge, clears one per non-edge, or transposes 64 x 64 blocks.
// Transposing pays on dense rows (hamming8-4, 41 edges a word of row) and loses on sparse ones
// (the 3DMatch dump, 4.3 edges a word), so the threshold sits between (measured in BENCHMARK.md,
// section 5e); the same threshold on the non-edges decides for near-complete rows (section 69).
constexpr long long kTransposeBitsPerWord = 8;

BitGraph permuted(const BitGraph& g, const std::vector<int>& vertices,
                  SteadyClock::time_point deadline) {
  const int k = static_cast<int>(vertices.size()), W = g.words();
  BitGraph sub(k);
  long long bits = 0;  // one scattered write each on the direct path
  for (int v : vertices) bits += g.degree(v);
  // The complement's path scatters one clear per non-edge of g's rows: on near-cliques (the
  // decomposition's neighbourhoods at density 0.98, relabelled each round of recolours_within())
  // a fiftieth of the edges.
  const long long non_edges = static_cast<long long>(k) * (g.size() - 1) - bits;
  const long long cheapest = std::min(bits, non_edges);
  if (cheapest < kTransposeBitsPerWord * static_cast<long long>(k) * W) {
    std::vector<int> index(static_cast<std::size_t>(g.size()), -1);
    for (int i = 0; i < k; ++i)
      index[static_cast<std::size_t>(vertices[static_cast<std::size_t>(i)])] = i;
    const bool complement = non_edges < bits;
    const std::vector<Word> all = complement ? first_n_set(k, sub.words()) : std::vector<Word>{};
    const std::vector<Word> in_g = complement ? first_n_set(g.size(), W) : std::vector<Word>{};
    for (int i = 0; i < k; ++i) {
      if ((i & 255) == 255) throw_if_past(deadline);
      Word* out = sub.row(i);
      const Word* row = g.row(vertices[static_cast<std::size_t>(i)]);
      if (!complement) {
        for_each_bit(row, W, [&](int u) {
          const int local = index[static_cast<std::size_t>(u)];
          if (local >= 0) out[local / kBits] |= Word{1} << (local % kBits);
        });
        continue;
      }
      // Every vertex of the result, then each non-neighbour (v itself among them) taken out.
      std::copy(all.begin(), all.end(), out);
      for (int w = 0; w < W; ++w) {
        for (Word x = ~row[w] & in_g[static_cast<std::size_t>(w)]; x; x &= x - 1) {
          const int local = index[static_cast<std::size_t>(w * kBits + lowest_bit(x))];
          if (local >= 0) out[local / kBits] &= ~(Word{1} << (local % kBits));
        }
      }
    }
    return sub;
  }
  // Dense rows: R (row i = g's row of vertices[i]) transposed in 64 x 64 blocks gives T, whose row
  // u has bit i set when vertices[i] ~ u; by symmetry, row vertices[j] of T is row j of the result.
  const int Wk = sub.words();
  std::vector<Word> T(static_cast<std::size_t>(W) * kBits * static_cast<std::size_t>(Wk), 0);
  Word block[kBits];
  for (int bi = 0; bi < Wk; ++bi) {
    if ((bi & 3) == 3) throw_if_past(deadline);
    for (int bj = 0; bj < W; ++bj) {
      Word any = 0;
      for (int r = 0; r < kBits; ++r) {
        const int i = bi * kBits + r;
        block[r] = i < k ? g.row(vertices[static_cast<std::size_t>(i)])[bj] : 0;
        any |= block[r];
      }
      if (!any) continue;
      BitGraph::transpose_block(block);
      for (int c = 0; c < kBits; ++c)
        T[static_cast<std::size_t>(bj * kBits + c) * static_cast<std::size_t>(Wk) +
          static_cast<std::size_t>(bi)] = block[c];
    }
  }
  for (int j = 0; j < k; ++j) {
    const Word* src = T.data() + static_cast<std::size_t>(vertices[static_cast<std::size_t>(j)]) *
                                     static_cast<std::size_t>(Wk);
    std::copy(src, src + Wk, sub.row(j));
  }
  return sub;
}

bool recolours_within(const BitGraph& g, int k, const Recolouring& r, std::vector<int>* counts) {
  const int n = g.size();
  if (n <= k) return true;
  const auto W = static_cast<std::size_t>(g.words());
  const std::vector<Word> all = first_n_set(n, g.words());
  std::vector<Word> U(W), Q(W);
  std::vector<int> ord(static_cast<std::size_t>(n)), col(ord.size()), next(ord.size());
  std::vector<int> at(ord.size()), first, classes_in;
  std::iota(at.begin(), at.end(), 0);  // at[i]: the vertex of g at position i of `order`
  BitGraph order;
  const BitGraph* current = &g;
  int fewest = n + 1, stale = 0;
  for (int round = 0; round < r.max_rounds; ++round) {
    int classes = 0, coloured = 0;
    colour_kernel(all.data(), g.words(), current->row(0), 1, U.data(), Q.data(), ord.data(),
                  col.data(), &classes, &coloured);
    if (counts) counts->push_back(classes);
    if (classes <= k) return true;
    if (round == 0 && classes > k + k / r.slack_divisor) return false;
    if (classes < fewest) {
      fewest = classes;
      stale = 0;
    } else if (++stale >= r.patience) {
      return false;
    }
    // ord lists the vertices class by class, classes ascending: class c is [first[c], first[c+1]).
    first.assign(static_cast<std::size_t>(classes) + 2, 0);
    for (int i = 0; i < n; ++i) {
      ++first[static_cast<std::size_t>(col[static_cast<std::size_t>(i)]) + 1];
    }
    std::partial_sum(first.begin(), first.end(), first.begin());
    auto size_of = [&](int c) {
      return first[static_cast<std::size_t>(c) + 1] - first[static_cast<std::size_t>(c)];
    };
    // The classes in reverse order, then largest first, alternately: either alone stalls sooner.
    classes_in.resize(static_cast<std::size_t>(classes));
    for (int c = 0; c < classes; ++c) classes_in[static_cast<std::size_t>(c)] = classes - c;
    if (round % 2 == 1) {
      std::stable_sort(classes_in.begin(), classes_in.end(),
                       [&](int a, int b) { return size_of(a) > size_of(b); });
    }
    std::size_t put = 0;
    for (int c : classes_in) {
      for (int i = first[static_cast<std::size_t>(c)]; i < first[static_cast<std::size_t>(c) + 1];
           ++i) {
        next[put++] = at[static_cast<std::size_t>(ord[static_cast<std::size_t>(i)])];
      }
    }
    at.swap(next);
    order = permuted(g, at);
    current = &order;
  }
  return false;
}

bool colours_within(const BitGraph& g, int k) {
  const auto W = static_cast<std::size_t>(g.words());
  const std::vector<Word> all = first_n_set(g.size(), g.words());
  std::vector<Word> U(W), Q(W);
  std::vector<int> ord(static_cast<std::size_t>(g.size())), col(ord.size());
  int classes = 0, coloured = 0;
  return colour_kernel(all.data(), g.words(), g.row(0), k + 1, U.data(), Q.data(), ord.data(),
                       col.data(), &classes, &coloured) == 0;
}

}  // namespace verifybench::detail
