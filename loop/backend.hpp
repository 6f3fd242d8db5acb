#pragma once
// The loop's back end (issue #29): the pose graph of the local maps (odometry edges between
// consecutive maps, one loop edge per accepted closure; loop/pose_graph.hpp) solved into the maps'
// corrected anchors. Each kind is an entry of the name-keyed registry below (core/registry.hpp);
// the loop solves every solver's graph with "plain" and with "robust" and reports both:
//   plain   Ceres, every edge a plain least-squares term (the paper's back end)
//   robust  Ceres, a Cauchy loss (scale 1 on the whitened residual) on loop edges: false loops
//           are shrugged off
// Both in backend_ceres.cpp; a new back end is one file defining a BackendInfo and one line in
// backend.cpp's list (or a call to register_backend).
#include <functional>
#include <string>
#include <vector>

#include "loop/pose_graph.hpp"

namespace verifybench {

struct BackendInfo {
  std::string name;
  std::string help;  ///< one line
  /// The optimised anchors from the odometry's (`initial`, the first held fixed) and the edges.
  /// Throws std::invalid_argument for an edge naming a missing node or a bad sigma.
  std::function<PoseGraphResult(const std::vector<Rigid<3>>& initial,
                                const std::vector<PoseEdge>& edges)>
      solve;
};

/// The back ends, in the order added: plain, robust.
std::vector<BackendInfo> list_backends();
/// The back end `name`. Throws UnknownName (core/registry.hpp, a std::invalid_argument): "unknown
/// back end 'NAME' (did you mean 'NEAR'?; known: plain, robust)".
const BackendInfo& find_backend(const std::string& name);
/// Adds a back end (std::logic_error on a duplicate name).
void register_backend(BackendInfo info);

// The kinds (backend_ceres.cpp).
BackendInfo ceres_plain_backend();
BackendInfo ceres_robust_backend();

}  // namespace verifybench
