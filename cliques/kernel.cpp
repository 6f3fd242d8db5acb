// CliqueKernel: vertex-cover reductions of the complement, on G's rows (cliques/detail/kernel.hpp).
#include "cliques/detail/kernel.hpp"

#include <algorithm>

namespace verifybench::detail {

CliqueKernel::CliqueKernel(const BitGraph& g, int max_rounds)
    : n_(g.size()),
      W_(g.words()),
      rows_(static_cast<std::size_t>(g.size()) * static_cast<std::size_t>(g.words())),
      alive_(first_n_set(g.size(), g.words())),
      out_(static_cast<std::size_t>(g.words())) {
  for (int v = 0; v < n_; ++v) std::copy(g.row(v), g.row(v) + W_, row(v));
  bool changed = true;
  for (int round = 0; changed && round < max_rounds; ++round) {
    changed = false;
    for (int v = 0; v < n_; ++v) {
      if (!alive(v)) continue;
      const int count = non_neighbours(v);
      if (take_if_simplicial(v, count)) {
        changed = true;
      } else if (count == 2) {  // not simplicial: its two non-neighbours are adjacent
        int ab[2], k = 0;
        for_each_bit(out_.data(), W_, [&](int u) { ab[k++] = u; });
        fold(v, ab[0], ab[1]);
        changed = true;
      } else if (drop_if_dominated(v)) {
        changed = true;
      }
    }
  }
  std::vector<int> index(static_cast<std::size_t>(n_), -1);
  for_each_bit(alive_.data(), W_, [&](int v) {
    index[static_cast<std::size_t>(v)] = static_cast<int>(kept_.size());
    kept_.push_back(v);
  });
  kernel_ = BitGraph(static_cast<int>(kept_.size()));
  for (std::size_t i = 0; i < kept_.size(); ++i) {
    const Word* r = row(kept_[i]);
    for (int w = kept_[i] / kBits; w < W_; ++w) {
      for (Word x = r[w] & alive_[static_cast<std::size_t>(w)]; x; x &= x - 1) {
        const int u = w * kBits + lowest_bit(x);
        if (u > kept_[i]) kernel_.add_edge(static_cast<int>(i), index[static_cast<std::size_t>(u)]);
      }
    }
  }
}

int CliqueKernel::non_neighbours(int v) {
  const Word* r = row(v);
  int count = 0;
  for (int w = 0; w < W_; ++w) {
    out_[static_cast<std::size_t>(w)] = alive_[static_cast<std::size_t>(w)] & ~r[w];
    if (w == v / kBits) out_[static_cast<std::size_t>(w)] &= ~(Word{1} << (v % kBits));
    count += __builtin_popcountll(out_[static_cast<std::size_t>(w)]);
  }
  return count;
}

// v's non-neighbours (out_) pairwise non-adjacent: some maximum clique holds v.
bool CliqueKernel::take_if_simplicial(int v, int count) {
  if (count > 0) {
    bool independent = true;
    for (int w = 0; w < W_ && independent; ++w) {
      for (Word x = out_[static_cast<std::size_t>(w)]; x && independent; x &= x - 1) {
        const Word* r = row(w * kBits + lowest_bit(x));
        for (int y = 0; y < W_; ++y) {
          if (r[y] & out_[static_cast<std::size_t>(y)]) {
            independent = false;
            break;
          }
        }
      }
    }
    if (!independent) return false;
  }
  steps_.push_back({Step::kTake, v, -1, -1});
  ++credit_;
  drop(v);
  for (int w = 0; w < W_; ++w)
    alive_[static_cast<std::size_t>(w)] &= ~out_[static_cast<std::size_t>(w)];
  return true;
}

// u dominated: some non-neighbour w has every neighbour of u left.
bool CliqueKernel::drop_if_dominated(int u) {
  const Word* ru = row(u);
  for (int w = 0; w < W_; ++w) {
    for (Word x = out_[static_cast<std::size_t>(w)]; x; x &= x - 1) {
      const Word* rv = row(w * kBits + lowest_bit(x));
      bool inside = true;
      for (int y = 0; y < W_ && inside; ++y) {
        inside = (ru[y] & alive_[static_cast<std::size_t>(y)] & ~rv[y]) == 0;
      }
      if (inside) {
        drop(u);
        return true;
      }
    }
  }
  return false;
}

// a stands for a and b from here: adjacent to their common neighbours.
void CliqueKernel::fold(int v, int a, int b) {
  steps_.push_back({Step::kFold, v, a, b});
  ++credit_;
  drop(v);
  drop(b);
  Word* ra = row(a);
  const Word* rb = row(b);
  for (int w = 0; w < W_; ++w) ra[w] &= rb[w] & alive_[static_cast<std::size_t>(w)];
  const Word bit = Word{1} << (a % kBits);
  for_each_bit(alive_.data(), W_, [&](int x) {
    Word& word = row(x)[a / kBits];
    word = (ra[x / kBits] >> (x % kBits)) & 1 ? word | bit : word & ~bit;
  });
}

std::vector<int> CliqueKernel::lift(const std::vector<int>& kernel_clique) const {
  std::vector<char> in(static_cast<std::size_t>(n_), 0);
  for (int k : kernel_clique) in[static_cast<std::size_t>(kept_[static_cast<std::size_t>(k)])] = 1;
  for (auto s = steps_.rbegin(); s != steps_.rend(); ++s) {
    if (s->kind == Step::kTake) {
      in[static_cast<std::size_t>(s->v)] = 1;
    } else if (in[static_cast<std::size_t>(s->a)]) {
      in[static_cast<std::size_t>(s->b)] = 1;
    } else {
      in[static_cast<std::size_t>(s->v)] = 1;
    }
  }
  std::vector<int> clique;
  for (int v = 0; v < n_; ++v) {
    if (in[static_cast<std::size_t>(v)]) clique.push_back(v);
  }
  return clique;
}

}  // namespace verifybench::detail
