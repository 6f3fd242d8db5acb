#include "core/compatibility_graph.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace verifybench {

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
  BitGraph g(static_cast<int>(n));
  const auto& m = corr.source;
  const auto& q = corr.target;
  const int count = static_cast<int>(n);
  for (int i = 0; i < count; ++i) {
    const Eigen::Matrix<double, Dim, 1> mi = m.col(i), qi = q.col(i);
    for (int j = i + 1; j < count; ++j) {
      // Eq. (1): compare the pair's length in both frames.
      const double dm = (m.col(j) - mi).norm();
      const double dq = (q.col(j) - qi).norm();
      if (std::abs(dm - dq) < params.eps) g.add_edge(i, j);
    }
  }
  return g;
}

template BitGraph build_compatibility_graph<2>(const Correspondences<2>&, const GraphParams&);
template BitGraph build_compatibility_graph<3>(const Correspondences<3>&, const GraphParams&);

}  // namespace verifybench
