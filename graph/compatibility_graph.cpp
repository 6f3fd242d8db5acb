#include "graph/compatibility_graph.hpp"

#include "core/timer.hpp"

#include <optional>

#include <atomic>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/detail/multiversion.hpp"
#include "core/parallel.hpp"

namespace verifybench {

namespace {

using Word = BitGraph::Word;

// Eq. (1) for one row in single precision: flags[j] bit 0 = | ||m_j - m_i|| - ||q_j - q_i|| | <
// eps, bit 1 = the float result is within `band` of eps and must be decided again in double.
// Structure- of-arrays input so that the loop vectorises (16 lanes with AVX-512); compiled for
// AVX-512, AVX2 and baseline x86-64 and picked at load time.

VB_MULTIVERSION
void row_flags_3d(const float* const* c, const float* p, int count, float eps, float band,
                  std::uint8_t* flags) {
  const float *mx = c[0], *my = c[1], *mz = c[2], *qx = c[3], *qy = c[4], *qz = c[5];
  for (int j = 0; j < count; ++j) {
    const float ax = mx[j] - p[0], ay = my[j] - p[1], az = mz[j] - p[2];
    const float bx = qx[j] - p[3], by = qy[j] - p[4], bz = qz[j] - p[5];
    const float d =
        std::fabs(std::sqrt(ax * ax + ay * ay + az * az) - std::sqrt(bx * bx + by * by + bz * bz));
    flags[j] = static_cast<std::uint8_t>((d < eps) | ((std::fabs(d - eps) < band) << 1));
  }
}

VB_MULTIVERSION
void row_flags_2d(const float* const* c, const float* p, int count, float eps, float band,
                  std::uint8_t* flags) {
  const float *mx = c[0], *my = c[1], *qx = c[2], *qy = c[3];
  for (int j = 0; j < count; ++j) {
    const float ax = mx[j] - p[0], ay = my[j] - p[1];
    const float bx = qx[j] - p[2], by = qy[j] - p[3];
    const float d = std::fabs(std::sqrt(ax * ax + ay * ay) - std::sqrt(bx * bx + by * by));
    flags[j] = static_cast<std::uint8_t>((d < eps) | ((std::fabs(d - eps) < band) << 1));
  }
}

/// Eight 0/1 bytes to eight bits (byte k -> bit k): one multiply, no carries between terms.
inline Word pack8(const std::uint8_t* flags) {
  std::uint64_t v;
  std::memcpy(&v, flags, 8);
  return ((v & 0x0101010101010101ull) * 0x0102040810204080ull) >> 56;
}

/// Coordinates for the float kernel: centred (distances do not change) so that float keeps as many
/// digits as possible, and the uncertainty band that covers float rounding for this extent.
template <int Dim>
struct FloatColumns {
  std::vector<std::vector<float>> cols;  // m_x, m_y, (m_z,) q_x, q_y, (q_z), padded by 64
  float band = 0;

  FloatColumns(const Correspondences<Dim>& corr, double eps) : cols(2 * Dim) {
    const auto n = static_cast<std::size_t>(corr.size());
    double extent = 0;
    for (int side = 0; side < 2; ++side) {
      const auto& pts = side == 0 ? corr.source : corr.target;
      // No mean of an empty set: Eigen offsets its null data pointer there (undefined behaviour).
      const Eigen::Matrix<double, Dim, 1> mean =
          n > 0 ? Eigen::Matrix<double, Dim, 1>(pts.rowwise().mean())
                : Eigen::Matrix<double, Dim, 1>::Zero();
      for (int d = 0; d < Dim; ++d) {
        auto& col = cols[static_cast<std::size_t>(side * Dim + d)];
        col.assign(n + 64, 0.0f);
        for (std::size_t i = 0; i < n; ++i) {
          const double x = pts(d, static_cast<Eigen::Index>(i)) - mean(d);
          extent = std::max(extent, std::abs(x));
          col[i] = static_cast<float>(x);
        }
      }
    }
    // Float error of |a - b| is below about 2.3e-6 * extent (rounding of centred coordinates,
    // differences, squares and roots); the band is 4x that, plus the rounding of eps itself.
    band = static_cast<float>(1e-5 * extent + 1e-6 * eps + 1e-12);
  }
};

/// Fills the upper triangle (bits j > i of row i) for rows first, first + step, ...
template <int Dim>
void fill_upper_rows(BitGraph& g, const Correspondences<Dim>& corr, const FloatColumns<Dim>& fc,
                     double eps, int first, int step,
                     const std::optional<SteadyClock::time_point>& deadline,
                     std::atomic<bool>& stop) {
  const int n = g.size();
  std::vector<std::uint8_t> flags(static_cast<std::size_t>(n) + 64, 0);
  const float* cols[2 * Dim];
  for (int k = 0; k < 2 * Dim; ++k) cols[k] = fc.cols[static_cast<std::size_t>(k)].data();
  const float eps_f = static_cast<float>(eps);
  for (int i = first, done = 0; i < n; i += step, ++done) {
    if (deadline && done % 32 == 0) {
      if (stop.load(std::memory_order_relaxed) || SteadyClock::now() > *deadline) {
        stop.store(true, std::memory_order_relaxed);
        return;
      }
    }
    // Start at the word holding bit i + 1; bits <= i of that word are cleared below.
    const int w0 = (i + 1) / BitGraph::kWordBits;
    const int j0 = w0 * BitGraph::kWordBits;
    if (j0 >= n) continue;
    float p[2 * Dim];
    for (int k = 0; k < 2 * Dim; ++k) p[k] = cols[k][i];
    const float* shifted[2 * Dim];
    for (int k = 0; k < 2 * Dim; ++k) shifted[k] = cols[k] + j0;
    const int count = n - j0;
    if constexpr (Dim == 3)
      row_flags_3d(shifted, p, count, eps_f, fc.band, flags.data());
    else
      row_flags_2d(shifted, p, count, eps_f, fc.band, flags.data());
    std::memset(flags.data() + count, 0, 64);
    // Pairs too close to eps for float: decide them in double (rare: a band of ~1e-5 extent).
    for (int j = 0; j < count; j += 8) {
      std::uint64_t v;
      std::memcpy(&v, flags.data() + j, 8);
      if (!(v & 0x0202020202020202ull)) continue;
      for (int k = j; k < j + 8 && k < count; ++k) {
        if (flags[static_cast<std::size_t>(k)] & 2) {
          flags[static_cast<std::size_t>(k)] = compatible(corr, i, j0 + k, eps);
        }
      }
    }
    Word* row = g.row(i);
    for (int w = w0; w < g.words(); ++w) {
      const std::uint8_t* f = flags.data() + static_cast<std::size_t>(w - w0) * 64;
      Word bits = 0;
      for (int b = 0; b < 8; ++b) bits |= pack8(f + 8 * b) << (8 * b);
      row[w] = bits;
    }
    const int bit = i % BitGraph::kWordBits;
    if (w0 == i / BitGraph::kWordBits) row[w0] &= ~((Word{2} << bit) - 1);  // keep bits > i only
  }
}

/// Lower triangle from the upper one, a 64x64 block at a time.
void mirror(BitGraph& g) {
  const int n = g.size(), W = g.words();
  Word block[64];
  for (int I = 0; I < W; ++I) {
    for (int J = I; J < W; ++J) {
      for (int r = 0; r < 64; ++r) {
        const int i = I * 64 + r;
        block[r] = i < n ? g.row(i)[J] : 0;
      }
      BitGraph::transpose_block(block);
      for (int r = 0; r < 64; ++r) {
        const int j = J * 64 + r;
        if (j < n) g.row(j)[I] |= block[r];
      }
    }
  }
}

}  // namespace

template <int Dim>
BitGraph build_compatibility_graph(const Correspondences<Dim>& corr, const GraphParams& params) {
  if (!(params.eps > 0.0) || !std::isfinite(params.eps)) {
    std::ostringstream msg;
    msg << "eps must be a positive finite distance, got " << params.eps;
    throw std::invalid_argument(msg.str());
  }
  const auto n = static_cast<std::size_t>(corr.size());
  const std::size_t bytes = BitGraph::bytes_for(n);
  if (bytes > params.max_bytes) {
    std::ostringstream msg;
    msg << "correspondence graph of " << n << " vertices needs " << bytes / (1 << 20)
        << " MiB of adjacency rows, over the cap of " << params.max_bytes / (1 << 20) << " MiB";
    throw std::length_error(msg.str());
  }
  std::optional<SteadyClock::time_point> deadline;
  if (params.time_limit_s > 0.0) deadline = deadline_after(params.time_limit_s);
  BitGraph g(static_cast<int>(n));
  const FloatColumns<Dim> fc(corr, params.eps);
  const int threads =
      std::max(1, std::min(resolve_threads(params.threads), static_cast<int>(n / 256) + 1));
  // Rows interleaved across workers: each writes only its own rows, so the graph is the same for
  // any thread count.
  std::atomic<bool> stop{false};
  WorkerPool workers(threads);
  workers.parallel_for(threads, [&](int t) {
    fill_upper_rows<Dim>(g, corr, fc, params.eps, t, threads, deadline, stop);
  });
  if (stop.load()) {
    throw DeadlinePassed("the time limit passed while building the correspondence graph (" +
                         std::to_string(n) + " vertices)");
  }
  mirror(g);
  return g;
}

template BitGraph build_compatibility_graph<2>(const Correspondences<2>&, const GraphParams&);
template BitGraph build_compatibility_graph<3>(const Correspondences<3>&, const GraphParams&);

}  // namespace verifybench
