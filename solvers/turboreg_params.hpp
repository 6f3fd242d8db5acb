#pragma once
// `turboreg`'s settings: a plain struct; its rows (CLI option, range, help, Python keyword) are
// declared in turboreg_solver.cpp.

namespace verifybench {

/// TurboReg (Yan et al., ICCV 2025); defaults from the authors' 3DMatch commands and code.
struct TurboRegParams {
  int pivots = 2000;           ///< K1: pivot edges, the heaviest by SC2
  int cliques_per_pivot = 2;   ///< K2: TurboCliques kept per pivot
  double tau_ratio = 0.12;     ///< the TurboClique graph's tau = tau_ratio * eps
  double nms_radius = 0.15;    ///< drop pairs with ||m_i - m_j|| + ||q_i - q_j|| <= this [m]
  int metric = 0;              ///< model selection: 0 = inlier count, 1 = MAE, 2 = MSE
  bool full_graph = false;     ///< third vertex from the SC2 graph, not the ordered O2Graph
  int refine_iterations = 20;  ///< reweighted refits of the winning motion at most
};

}  // namespace verifybench
