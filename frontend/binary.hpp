#pragma once
// Binary descriptors (B-SHOT: 352 bits, ORB: 256 bits) stored contiguously, and their Hamming
// distance.
#include <cstdint>
#include <vector>

namespace verifybench {

struct BinaryDescriptors {
  using Word = std::uint64_t;
  int bits = 0;            ///< bits per descriptor
  std::vector<Word> data;  ///< words() words per descriptor, unused high bits zero

  explicit BinaryDescriptors(int bits_per_descriptor = 0) : bits(bits_per_descriptor) {}
  int words() const { return (bits + 63) / 64; }
  int size() const { return words() == 0 ? 0 : static_cast<int>(data.size()) / words(); }
  const Word* row(int i) const { return data.data() + static_cast<std::size_t>(i) * words(); }
  Word* row(int i) { return data.data() + static_cast<std::size_t>(i) * words(); }
  /// Appends one all-zero descriptor and returns it.
  Word* add() {
    data.resize(data.size() + static_cast<std::size_t>(words()), 0);
    return row(size() - 1);
  }
  bool bit(int i, int b) const { return (row(i)[b / 64] >> (b % 64)) & 1u; }
};

inline int hamming(const std::uint64_t* a, const std::uint64_t* b, int words) {
  int d = 0;
  for (int w = 0; w < words; ++w) d += __builtin_popcountll(a[w] ^ b[w]);
  return d;
}

struct BinaryMatch {
  int index = -1;  ///< -1 when nothing is within the threshold
  int distance = 0;
};

/// Improves `best` (ties: lowest index) with the descriptors `ids[0..count)` of `set`, or with
/// all of them when `ids` is null. Compiled for POPCNT/AVX2/AVX-512 and baseline x86-64 and picked
/// at load time (a plain build has no hardware popcount).
void scan_nearest(const BinaryDescriptors& set, const int* ids, int count,
                  const std::uint64_t* query, BinaryMatch& best);

/// Nearest descriptor of `set` to `query` within `max_distance` by exhaustive search: the
/// reference every faster matcher is checked against. Ties go to the lowest index.
inline BinaryMatch brute_force_nearest(const BinaryDescriptors& set, const std::uint64_t* query,
                                       int max_distance) {
  BinaryMatch best;
  best.distance = max_distance + 1;
  scan_nearest(set, nullptr, set.size(), query, best);
  if (best.index < 0) best.distance = 0;
  return best;
}

}  // namespace verifybench
