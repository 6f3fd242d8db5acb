#include "harness/builtin.hpp"

#include "cliques/max_clique.hpp"
#include "peers/peers.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

void register_builtin_solvers() {
  register_clique_algorithms();
  register_solvers();
  register_peer_solvers();
}

}  // namespace verifybench
