#pragma once
// Seeds: every random draw in verifybench comes from a std::mt19937_64 seeded from a user seed.
#include <cstdint>
#include <initializer_list>

namespace verifybench {

/// SplitMix64 finaliser: a well-mixed 64-bit value from one input.
constexpr std::uint64_t mix_seed(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// A child seed for (base, stream ids...), so that trials and solvers draw independent streams that
/// do not depend on the order in which they run.
inline std::uint64_t derive_seed(std::uint64_t base, std::initializer_list<std::uint64_t> ids) {
  std::uint64_t s = mix_seed(base);
  for (std::uint64_t id : ids) s = mix_seed(s ^ mix_seed(id + 0x632BE59BD9B4E019ull));
  return s;
}

}  // namespace verifybench
