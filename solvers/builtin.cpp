#include <mutex>

#include "solvers/registry.hpp"

namespace verifybench {

void register_clique_solvers();
void register_ransac_solver();
void register_mac_solver();
void register_jcbb_solver();
void register_gnc_tls_solver();
void register_teaser_solver();
void register_sc2pcr_solver();
void register_robin_gnc_solver();
void register_quatro_solver();
void register_turboreg_solver();
void register_clipper_solver();
void register_fastmac_solver();

void register_solvers() {
  static std::once_flag once;
  std::call_once(once, [] {
    register_clique_solvers();
    register_ransac_solver();
    register_mac_solver();
    register_jcbb_solver();
    register_gnc_tls_solver();
    register_teaser_solver();
    register_sc2pcr_solver();
    register_robin_gnc_solver();
    register_quatro_solver();
    register_turboreg_solver();
    register_clipper_solver();
    register_fastmac_solver();
  });
}

}  // namespace verifybench
