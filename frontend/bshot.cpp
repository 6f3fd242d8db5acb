#include "frontend/bshot.hpp"

namespace verifybench {

std::uint8_t bshot_code(const float v[4]) {
  const float sum = v[0] + v[1] + v[2] + v[3];
  if (!(sum > 0.0f)) return 0;  // all zero (or a degenerate descriptor)
  const float share = 0.9f * sum;
  // Groups in the order of the published reference; the first that exceeds 90% wins.
  static constexpr std::uint8_t kGroups[] = {0b0001, 0b0010, 0b0100, 0b1000,          // one
                                             0b0011, 0b0110, 0b1100, 0b1001, 0b1010,  // two
                                             0b0101,                                  //
                                             0b0111, 0b1110, 0b1101, 0b1011};         // three
  for (std::uint8_t g : kGroups) {
    float s = 0.0f;
    for (int k = 0; k < 4; ++k) {
      if (g >> k & 1u) s += v[k];
    }
    if (s > share) return g;
  }
  return 0b1111;
}

void binarize_shot(const float shot[kShotLength], std::uint64_t out[6]) {
  for (int w = 0; w < 6; ++w) out[w] = 0;
  for (int g = 0; g < kShotLength / 4; ++g) {
    const std::uint64_t code = bshot_code(shot + 4 * g);
    out[(4 * g) / 64] |= code << ((4 * g) % 64);
  }
}

}  // namespace verifybench
