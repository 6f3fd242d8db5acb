#pragma once
// Undirected graph as bitset adjacency rows: row v has bit u set when {u, v} is an edge.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

namespace verifybench {

/// Zeroed words that are not written to be zero: calloc hands large blocks over as untouched zero
/// pages, so a graph's rows cost nothing until they are filled (n = 50,000 is 312 MB, whose
/// writing alone took longer than a 0.2 s time limit). Value-initialisation does nothing: only
/// for storage sized once, at construction, from calloc.
template <class T>
struct ZeroedAllocator {
  using value_type = T;
  ZeroedAllocator() = default;
  template <class U>
  explicit ZeroedAllocator(const ZeroedAllocator<U>&) {}
  T* allocate(std::size_t n) {
    void* p = std::calloc(n, sizeof(T));
    if (p == nullptr) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) { std::free(p); }
  template <class U>
  void construct(U*) noexcept {}  // already zero
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  friend bool operator==(const ZeroedAllocator&, const ZeroedAllocator&) { return true; }
  friend bool operator!=(const ZeroedAllocator&, const ZeroedAllocator&) { return false; }
};

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
  std::vector<Word, ZeroedAllocator<Word>> bits_;  ///< sized once, in the constructor
};

}  // namespace verifybench
