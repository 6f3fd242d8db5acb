#include <cmath>
#include <mutex>
#include <sstream>

#include "solvers/registry.hpp"

namespace verifybench {

void register_clique_solvers();
void register_ransac_solver();
void register_mac_solver();
void register_jcbb_solver();

void register_solvers() {
  static std::once_flag once;
  std::call_once(once, [] {
    register_clique_solvers();
    register_ransac_solver();
    register_mac_solver();
    register_jcbb_solver();
  });
}

const char* to_string(Status s) {
  switch (s) {
    case Status::ok:
      return "ok";
    case Status::rejected:
      return "rejected";
    case Status::time_limit:
      return "time_limit";
    case Status::error:
      return "error";
  }
  return "error";
}

void SolverParams::validate() const {
  auto require = [](bool ok, const char* field, auto value, const char* expected) {
    if (ok) return;
    std::ostringstream msg;
    msg << "solver parameter " << field << " = " << value << " is invalid; expected " << expected;
    throw std::invalid_argument(msg.str());
  };
  require(eps > 0.0 && std::isfinite(eps), "eps", eps, "a finite value > 0");
  require(inlier_threshold > 0.0 && std::isfinite(inlier_threshold), "inlier_threshold",
          inlier_threshold, "a finite value > 0");
  require(min_inliers >= 0, "min_inliers", min_inliers, "an integer >= 0 (0 = paper default)");
  require(time_limit_s > 0.0, "time_limit_s", time_limit_s, "a value > 0");
  require(ransac_iterations >= 1, "ransac_iterations", ransac_iterations, "an integer >= 1");
  require(mac_max_cliques >= 1, "mac_max_cliques", mac_max_cliques, "an integer >= 1");
  require(mac_min_clique >= 2, "mac_min_clique", mac_min_clique, "an integer >= 2");
  require(threads >= 0, "threads", threads, "an integer >= 0 (0 = all cores)");
  require(jcbb_sigma >= 0.0 && std::isfinite(jcbb_sigma), "jcbb_sigma", jcbb_sigma,
          "a finite value >= 0 (0 = inlier_threshold / 3)");
  require(jcbb_confidence > 0.0 && jcbb_confidence < 1.0, "jcbb_confidence", jcbb_confidence,
          "a value in (0, 1)");
  require(ransac_confidence > 0.0 && ransac_confidence < 1.0, "ransac_confidence",
          ransac_confidence, "a value in (0, 1)");
}

}  // namespace verifybench
