/* C shim around libcliquer: builds its graph from our bitset rows and runs
   clique_unweighted_find_single. */
#include "cliquer_shim.h"

#include <cliquer/cliquer.h>

int vb_cliquer_max_clique(int n, const unsigned long long* rows, int words, int* out) {
  if (n <= 0) return 0;
  graph_t* g = graph_new(n);
  if (!g) return -1;
  for (int i = 0; i < n; ++i) {
    const unsigned long long* row = rows + (long)i * words;
    for (int j = i + 1; j < n; ++j) {
      if ((row[j / 64] >> (j % 64)) & 1ull) GRAPH_ADD_EDGE(g, i, j);
    }
  }
  clique_options opts = *clique_default_options;
  opts.time_function = NULL; /* the default prints progress to stdout */
  opts.output = NULL;
  set_t clique = clique_unweighted_find_single(g, 0, 0, FALSE, &opts);
  int size = 0;
  if (clique) {
    for (int v = -1; (v = set_return_next(clique, v)) >= 0;) out[size++] = v;
    set_free(clique);
  }
  graph_free(g);
  return size;
}
