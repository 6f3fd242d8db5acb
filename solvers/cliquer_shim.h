/* C interface to Debian's libcliquer (whose headers do not compile as C++). */
#ifndef VERIFYBENCH_CLIQUER_SHIM_H
#define VERIFYBENCH_CLIQUER_SHIM_H
#ifdef __cplusplus
extern "C" {
#endif

/* Maximum clique of the graph with `n` vertices whose adjacency rows are `rows` (n rows of `words`
   64-bit words, bit j of row i set for edge {i, j}). Writes the clique's vertices to `out` (room
   for n) and returns its size, or -1 when cliquer could not allocate. Uses cliquer's default
   options (greedy-colouring vertex order) without progress output. */
int vb_cliquer_max_clique(int n, const unsigned long long* rows, int words, int* out);

#ifdef __cplusplus
}
#endif
#endif
