/* C interface to Debian's libcliquer (whose headers do not compile as C++). */
#ifndef VERIFYBENCH_CLIQUER_SHIM_H
#define VERIFYBENCH_CLIQUER_SHIM_H
#ifdef __cplusplus
extern "C" {
#endif

/* cliquer's own graph, built from `n` adjacency rows of `words` 64-bit words (bit j of row i set
   for edge {i, j}); NULL when cliquer could not allocate. Free with vb_cliquer_graph_free. */
typedef struct vb_cliquer_graph vb_cliquer_graph;
vb_cliquer_graph* vb_cliquer_graph_new(int n, const unsigned long long* rows, int words);
void vb_cliquer_graph_free(vb_cliquer_graph* g);

/* Maximum clique by clique_unweighted_find_single with cliquer's default options (greedy-colouring
   vertex order) and no progress output. Writes its vertices to `out` (room for n) and returns its
   size. */
int vb_cliquer_solve(const vb_cliquer_graph* g, int* out);

/* Both steps: returns the clique size, or -1 when cliquer could not allocate. */
int vb_cliquer_max_clique(int n, const unsigned long long* rows, int words, int* out);

#ifdef __cplusplus
}
#endif
#endif
