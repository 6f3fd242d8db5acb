#include "frontend/binary.hpp"

#include "core/detail/multiversion.hpp"

namespace verifybench {

VB_MULTIVERSION_POPCNT
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
