#pragma once
// The correspondence graph of CliReg: one vertex per correspondence, an edge {i, j} when
//   | ||m_i - m_j|| - ||q_i - q_j|| | < eps                                   (paper, Eq. 1)
// i.e. the pair keeps its length under the motion, as any two inliers of one rigid motion do.
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "core/correspondences.hpp"
#include "core/deadline.hpp"
#include "graph/bitgraph.hpp"

namespace verifybench {

struct GraphParams {
  double eps = 0.1;                              ///< pair length tolerance [m], > 0
  std::size_t max_bytes = std::size_t{4} << 30;  ///< refuse graphs whose rows exceed this
  int threads = 1;  ///< worker threads (0 = all cores); same graph for any count
  double time_limit_s = 0.0;  ///< > 0: give up past this many seconds (DeadlinePassed)
};

/// Eq. (1) for one pair in double precision: the definition every graph of it reproduces.
template <int Dim>
bool compatible(const Correspondences<Dim>& corr, int i, int j, double eps) {
  return std::abs((corr.source.col(i) - corr.source.col(j)).norm() -
                  (corr.target.col(i) - corr.target.col(j)).norm()) < eps;
}

/// Throws std::invalid_argument for eps <= 0, std::length_error (with the sizes) when the
/// adjacency rows would exceed params.max_bytes, DeadlinePassed when the time limit passed (the
/// clock is read every 32 rows).
template <int Dim>
BitGraph build_compatibility_graph(const Correspondences<Dim>& corr, const GraphParams& params);

}  // namespace verifybench
