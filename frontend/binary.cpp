#include "frontend/binary.hpp"

namespace verifybench {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "popcnt", "default")))
#endif
void scan_nearest(const BinaryDescriptors& set, const int* ids, int count,
                  const std::uint64_t* query, BinaryMatch& best) {
  const int words = set.words();
  for (int k = 0; k < count; ++k) {
    const int i = ids ? ids[k] : k;
    const std::uint64_t* row = set.row(i);
    int d = 0;
    for (int w = 0; w < words; ++w) d += __builtin_popcountll(row[w] ^ query[w]);
    if (d < best.distance || (d == best.distance && best.index >= 0 && i < best.index)) {
      best.index = i;
      best.distance = d;
    }
  }
}

}  // namespace verifybench
