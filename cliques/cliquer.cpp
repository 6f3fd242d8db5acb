// Peer: Debian's libcliquer (Ostergard's algorithm, through a C shim), in a killable child.
#include "cliques/detail/cliquer_shim.h"
#include "cliques/detail/peer_result.hpp"
#include "core/detail/killable_child.hpp"

namespace verifybench {

namespace {

using detail::peer_result;
using detail::run_in_child;

CliqueSearchResult run_cliquer(const BitGraph& g, const CliqueSearchParams& p) {
  static_assert(sizeof(unsigned long long) == sizeof(BitGraph::Word));
  return peer_result(run_in_child(deadline_after(p.time_limit_s),
                                  [&] {
                                    std::vector<int> out(static_cast<std::size_t>(g.size()));
                                    const int size = vb_cliquer_max_clique(
                                        g.size(),
                                        reinterpret_cast<const unsigned long long*>(g.row(0)),
                                        g.words(), out.data());
                                    if (size < 0) ::_exit(2);
                                    out.resize(static_cast<std::size_t>(size));
                                    return out;
                                  }),
                     g.size());
}

}  // namespace

void register_cliquer() {
  CliqueAlgorithms::add({"cliquer",
                         "peer: Debian libcliquer 1.21 (Ostergard), default options, via a C shim",
                         true, run_cliquer, /*child_process=*/true});
}

}  // namespace verifybench
