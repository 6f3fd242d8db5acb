#pragma once
// `clipper`'s settings: a plain struct; its rows (CLI option, range, help, Python keyword) are
// declared in clipper_solver.cpp. Defaults from the authors' code: CLIPPER+'s clique_optimization
// Params (ariarobotics/clipperp) for the gradient ascent, CLIPPER's registration examples
// (mit-acl/clipper) for the kernel width.

namespace verifybench {

/// `clipper`: CLIPPER+ (Fathian & Summers, RA-L 2024) on CLIPPER's weighted consistency graph
/// (Lusk, Fathian & How, ICRA 2021).
struct ClipperParams {
  double sigma = 0.0;        ///< kernel width of the pair scores [m]; 0 = eps / 2
  bool binary = false;       ///< unweighted affinity (CLIPPER+'s graphs): M = adjacency + I
  bool no_kcore = false;     ///< plain CLIPPER: no core-number heuristic clique, no pruning
  double tol_u = 1e-8;       ///< inner loop stops when ||u_new - u|| < tol_u
  double tol_f = 1e-9;       ///< inner loop stops when |F_new - F| < tol_f
  int max_inner = 200;       ///< gradient ascent steps per value of d
  int max_outer = 1000;      ///< increases of d at most
  int max_line_search = 20;  ///< backtracking steps per gradient step
  double beta = 0.5;         ///< backtracking factor of the step size, in (0, 1)
  double armijo = 0.01;      ///< sufficient-increase constant of the Armijo test, in (0, 1)
  double zero_eps = 1e-9;    ///< numerical zero: of u's entries, of C-bar u, and the rounding
};

}  // namespace verifybench
