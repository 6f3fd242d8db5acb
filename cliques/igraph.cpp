// Peer: libigraph's igraph_largest_cliques, in a killable child.
#include <igraph/igraph.h>

#include "cliques/detail/bbmc.hpp"
#include "cliques/detail/peer_result.hpp"
#include "core/detail/killable_child.hpp"

namespace verifybench {

namespace {

using detail::peer_result;
using detail::run_in_child;

std::vector<int> igraph_clique(const BitGraph& g) {
  igraph_set_error_handler(igraph_error_handler_ignore);  // return codes instead of abort()
  igraph_set_warning_handler(igraph_warning_handler_ignore);
  std::vector<int> clique;
  if (g.size() == 0) return clique;
  igraph_vector_int_t edges;
  igraph_vector_int_init(&edges, 0);
  for (int i = 0; i < g.size(); ++i) {
    detail::for_each_bit(g.row(i), g.words(), [&](int j) {
      if (j > i) {
        igraph_vector_int_push_back(&edges, i);
        igraph_vector_int_push_back(&edges, j);
      }
    });
  }
  igraph_t graph;
  igraph_create(&graph, &edges, g.size(), IGRAPH_UNDIRECTED);
  igraph_vector_int_destroy(&edges);
  igraph_vector_int_list_t cliques;
  igraph_vector_int_list_init(&cliques, 0);
  if (igraph_largest_cliques(&graph, &cliques) != IGRAPH_SUCCESS) ::_exit(3);
  if (igraph_vector_int_list_size(&cliques) > 0) {
    const igraph_vector_int_t* c = igraph_vector_int_list_get_ptr(&cliques, 0);
    for (igraph_integer_t k = 0; k < igraph_vector_int_size(c); ++k) {
      clique.push_back(static_cast<int>(VECTOR(*c)[k]));
    }
  }
  igraph_vector_int_list_destroy(&cliques);
  igraph_destroy(&graph);
  return clique;
}

CliqueSearchResult run_igraph(const BitGraph& g, const CliqueSearchParams& p) {
  return peer_result(run_in_child(deadline_after(p.time_limit_s), [&] { return igraph_clique(g); }),
                     g.size());
}

}  // namespace

void register_igraph() {
  CliqueAlgorithms::add(
      {"igraph", "peer: Debian libigraph 0.10 igraph_largest_cliques", true, run_igraph,
       /*child_process=*/true});
}

}  // namespace verifybench
