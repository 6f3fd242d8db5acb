// Back ends "plain" and "robust": the Ceres pose graph of loop/pose_graph.hpp (Levenberg-Marquardt,
// its default iterations), without a loss and with a Cauchy loss on loop edges.
#include "loop/backend.hpp"

namespace verifybench {

namespace {

BackendInfo ceres_backend(const std::string& name, const std::string& help, bool robust) {
  BackendInfo info;
  info.name = name;
  info.help = help;
  info.solve = [robust](const std::vector<Rigid<3>>& initial, const std::vector<PoseEdge>& edges) {
    PoseGraphParams params;
    params.robust = robust;
    return optimise_pose_graph(initial, edges, params);
  };
  return info;
}

}  // namespace

BackendInfo ceres_plain_backend() {
  return ceres_backend("plain", "Ceres pose graph, least squares on every edge", false);
}

BackendInfo ceres_robust_backend() {
  return ceres_backend("robust", "Ceres pose graph, a Cauchy loss on loop edges", true);
}

}  // namespace verifybench
