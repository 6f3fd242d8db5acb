// Scoring kernels of the RANSAC family. Blocks of kBlock points are scored with straight-line
// code the compiler vectorises (AVX-512, AVX2 or baseline, picked at load time); the early exit
// is checked between blocks. Built with -ffp-contract=off so that every path rounds alike.
#include "solvers/detail/ransac_kernels.hpp"

#include <algorithm>

#include "core/detail/multiversion.hpp"

namespace verifybench::detail {

namespace {

constexpr int kBlock = 128;

/// Squared residuals of points [begin, begin + count) into r2.
template <int Dim>
__attribute__((always_inline)) inline void residuals(const ScoringPoints& p, const CentredMotion& T,
                                                     int begin, int count, float* __restrict r2) {
  const float* sx = p.s[0].data() + begin;
  const float* sy = p.s[1].data() + begin;
  const float* tx = p.t[0].data() + begin;
  const float* ty = p.t[1].data() + begin;
  // Locals, so the compiler need not reload them in case r2 aliases the motion.
  const float r00 = T.R[0], r01 = T.R[1], r02 = T.R[2], r10 = T.R[3], r11 = T.R[4], r12 = T.R[5],
              r20 = T.R[6], r21 = T.R[7], r22 = T.R[8];
  const float t0 = T.t[0], t1 = T.t[1], t2 = T.t[2];
  if constexpr (Dim == 2) {
    for (int j = 0; j < count; ++j) {
      const float ex = r00 * sx[j] + r01 * sy[j] + t0 - tx[j];
      const float ey = r10 * sx[j] + r11 * sy[j] + t1 - ty[j];
      r2[j] = ex * ex + ey * ey;
    }
  } else {
    const float* sz = p.s[2].data() + begin;
    const float* tz = p.t[2].data() + begin;
    for (int j = 0; j < count; ++j) {
      const float ex = r00 * sx[j] + r01 * sy[j] + r02 * sz[j] + t0 - tx[j];
      const float ey = r10 * sx[j] + r11 * sy[j] + r12 * sz[j] + t1 - ty[j];
      const float ez = r20 * sx[j] + r21 * sy[j] + r22 * sz[j] + t2 - tz[j];
      r2[j] = ex * ex + ey * ey + ez * ez;
    }
  }
}

template <int Dim>
__attribute__((always_inline)) inline int count_impl(const ScoringPoints& p, const CentredMotion& T,
                                                     float thr2, int bound) {
  alignas(64) float r2[kBlock];
  int count = 0;
  for (int begin = 0; begin < p.n; begin += kBlock) {
    const int len = std::min(kBlock, p.n - begin);
    residuals<Dim>(p, T, begin, len, r2);
    int c = 0;
    for (int j = 0; j < len; ++j) c += r2[j] < thr2;
    count += c;
    if (count + (p.n - begin - len) <= bound) return count;  // cannot beat the bound any more
  }
  return count;
}

template <int Dim>
__attribute__((always_inline)) inline std::int64_t msac_impl(const ScoringPoints& p,
                                                             const CentredMotion& T, float thr2,
                                                             std::int64_t bound) {
  alignas(64) float r2[kBlock];
  const float scale = static_cast<float>(kMsacUnits) / thr2;
  std::int64_t cost = 0;
  for (int begin = 0; begin < p.n; begin += kBlock) {
    const int len = std::min(kBlock, p.n - begin);
    residuals<Dim>(p, T, begin, len, r2);
    std::int32_t c = 0;
    for (int j = 0; j < len; ++j) {
      c += static_cast<std::int32_t>(std::min(r2[j], thr2) * scale);
    }
    cost += c;
    if (cost >= bound) return cost;
  }
  return cost;
}

VB_MULTIVERSION int count_2d(const ScoringPoints& p, const CentredMotion& T, float thr2, int b) {
  return count_impl<2>(p, T, thr2, b);
}
VB_MULTIVERSION int count_3d(const ScoringPoints& p, const CentredMotion& T, float thr2, int b) {
  return count_impl<3>(p, T, thr2, b);
}
VB_MULTIVERSION std::int64_t msac_2d(const ScoringPoints& p, const CentredMotion& T, float thr2,
                                     std::int64_t b) {
  return msac_impl<2>(p, T, thr2, b);
}
VB_MULTIVERSION std::int64_t msac_3d(const ScoringPoints& p, const CentredMotion& T, float thr2,
                                     std::int64_t b) {
  return msac_impl<3>(p, T, thr2, b);
}

}  // namespace

template <int Dim>
ScoringPoints make_scoring_points(const Correspondences<Dim>& corr) {
  ScoringPoints p;
  p.dim = Dim;
  p.n = static_cast<int>(corr.size());
  if (p.n > 0) {
    p.source_centroid.head<Dim>() = corr.source.rowwise().mean();
    p.target_centroid.head<Dim>() = corr.target.rowwise().mean();
  }
  for (int d = 0; d < Dim; ++d) {
    p.s[d].resize(static_cast<std::size_t>(p.n));
    p.t[d].resize(static_cast<std::size_t>(p.n));
    for (int i = 0; i < p.n; ++i) {
      p.s[d][static_cast<std::size_t>(i)] =
          static_cast<float>(corr.source(d, i) - p.source_centroid(d));
      p.t[d][static_cast<std::size_t>(i)] =
          static_cast<float>(corr.target(d, i) - p.target_centroid(d));
    }
  }
  return p;
}

template <int Dim>
CentredMotion centre(const ScoringPoints& pts, const Rigid<Dim>& T) {
  // q - c_t = R (m - c_s) + (R c_s + t - c_t)
  CentredMotion out;
  const Eigen::Matrix<double, Dim, 1> t = T.linear() * pts.source_centroid.head<Dim>() +
                                          T.translation() - pts.target_centroid.head<Dim>();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      out.R[3 * r + c] = (r < Dim && c < Dim) ? static_cast<float>(T.linear()(r, c)) : 0.0f;
    }
    out.t[r] = r < Dim ? static_cast<float>(t(r)) : 0.0f;
  }
  return out;
}

int count_inliers(const ScoringPoints& pts, const CentredMotion& T, float thr2, int bound) {
  return pts.dim == 2 ? count_2d(pts, T, thr2, bound) : count_3d(pts, T, thr2, bound);
}

std::int64_t msac_cost(const ScoringPoints& pts, const CentredMotion& T, float thr2,
                       std::int64_t bound) {
  return pts.dim == 2 ? msac_2d(pts, T, thr2, bound) : msac_3d(pts, T, thr2, bound);
}

template ScoringPoints make_scoring_points<2>(const Correspondences<2>&);
template ScoringPoints make_scoring_points<3>(const Correspondences<3>&);
template CentredMotion centre<2>(const ScoringPoints&, const Rigid<2>&);
template CentredMotion centre<3>(const ScoringPoints&, const Rigid<3>&);

}  // namespace verifybench::detail
