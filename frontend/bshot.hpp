#pragma once
// B-SHOT (Prakhya, Liu & Lin, IROS 2015): a SHOT descriptor (32 spatial bins x 11 angle bins =
// 352 floats) binarised four values at a time into four bits, so that Hamming distance replaces
// Euclidean distance.
#include <cstdint>

namespace verifybench {

constexpr int kShotLength = 352;

/// Four values v (non-negative) with sum S become the bits of the smallest group of them that
/// holds more than 90% of S, tried in the published order: nothing when all are 0; one value
/// (v0, v1, v2, v3); two (01, 12, 23, 03, 13, 02); three (012, 123, 023, 013); else all four.
/// Returns the 4-bit code, bit k set when value k is in the group.
std::uint8_t bshot_code(const float v[4]);

/// All 88 groups of a SHOT descriptor: group g fills bits 4g .. 4g + 3 of `out` (6 words, the
/// last 32 bits zero).
void binarize_shot(const float shot[kShotLength], std::uint64_t out[6]);

}  // namespace verifybench
