#include "peers/peers.hpp"

#include <mutex>

namespace verifybench {

void register_pcl_solvers();     // pcl_solvers.cpp
void register_open3d_solvers();  // open3d_solver.cpp

void register_peer_solvers() {
  static std::once_flag once;
  std::call_once(once, [] {
#ifdef VERIFYBENCH_HAVE_PCL
    register_pcl_solvers();
#endif
#ifdef VERIFYBENCH_HAVE_OPEN3D
    register_open3d_solvers();
#endif
  });
}

}  // namespace verifybench
