/* C shim around libcliquer: builds its graph from our bitset rows and runs
   clique_unweighted_find_single. */
#include "detail/cliquer_shim.h"

#include <stdlib.h>

#include <cliquer/cliquer.h>

struct vb_cliquer_graph {
  graph_t* g;
};

vb_cliquer_graph* vb_cliquer_graph_new(int n, const unsigned long long* rows, int words) {
  if (n <= 0) return NULL;
  vb_cliquer_graph* handle = malloc(sizeof *handle);
  if (!handle) return NULL;
  handle->g = graph_new(n);
  if (!handle->g) {
    free(handle);
    return NULL;
  }
  for (int i = 0; i < n; ++i) {
    const unsigned long long* row = rows + (long)i * words;
    for (int j = i + 1; j < n; ++j) {
      if ((row[j / 64] >> (j % 64)) & 1ull) GRAPH_ADD_EDGE(handle->g, i, j);
    }
  }
  return handle;
}

void vb_cliquer_graph_free(vb_cliquer_graph* handle) {
  if (!handle) return;
  graph_free(handle->g);
  free(handle);
}

int vb_cliquer_solve(const vb_cliquer_graph* handle, int* out) {
  clique_options opts = *clique_default_options;
  opts.time_function = NULL; /* the default prints progress to stdout */
  opts.output = NULL;
  set_t clique = clique_unweighted_find_single(handle->g, 0, 0, FALSE, &opts);
  int size = 0;
  if (clique) {
    for (int v = -1; (v = set_return_next(clique, v)) >= 0;) out[size++] = v;
    set_free(clique);
  }
  return size;
}

int vb_cliquer_max_clique(int n, const unsigned long long* rows, int words, int* out) {
  if (n <= 0) return 0;
  vb_cliquer_graph* g = vb_cliquer_graph_new(n, rows, words);
  if (!g) return -1;
  const int size = vb_cliquer_solve(g, out);
  vb_cliquer_graph_free(g);
  return size;
}
