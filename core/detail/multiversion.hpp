#pragma once
// Kernels compiled several times and picked at load time by the CPU (GCC's target_clones): the
// build stays portable (no -march=native) and still uses AVX-512, AVX2 or POPCNT where present.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
/// Vector kernels: AVX-512 (x86-64-v4), AVX2 (x86-64-v3) and baseline x86-64.
#define VB_MULTIVERSION \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
/// Bit-counting kernels: as above plus a POPCNT-only clone for CPUs between the baseline and AVX2.
#define VB_MULTIVERSION_POPCNT \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "popcnt", "default")))
#else
#define VB_MULTIVERSION
#define VB_MULTIVERSION_POPCNT
#endif
