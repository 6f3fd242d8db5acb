#pragma once
// Synthetic correspondence sets with a drawn rigid motion and per-correspondence labels.
#include <cstdint>

#include "core/correspondences.hpp"

namespace verifybench {

struct SyntheticParams {
  int n = 500;                   ///< correspondences, >= 1
  double outlier_ratio = 0.5;    ///< fraction of outliers in [0, 1]; round(n * ratio) outliers
  double noise = 0.01;           ///< Gaussian sigma per axis added to inlier targets [m], >= 0
  double extent = 10.0;          ///< source points uniform in a cube (square) of this side [m], > 0
  double max_translation = 5.0;  ///< each translation component uniform in [-max, max] [m], >= 0
  std::uint64_t seed = 1;        ///< every draw comes from this seed
  void validate() const;         ///< throws std::invalid_argument naming the field and value
};

/// Source points m_i are uniform in the cube; inlier targets are q_i = T m_i + noise; outlier
/// targets are uniform in the cube's image under T (so outliers overlap inliers spatially). The
/// rotation is uniform on SO(Dim). Inliers and outliers are interleaved in a random order.
template <int Dim>
LabeledSet<Dim> make_synthetic(const SyntheticParams& params);

}  // namespace verifybench
