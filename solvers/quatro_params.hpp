#pragma once
// `quatro`'s settings: a plain struct; its rows (CLI option, range, help, Python keyword) are
// declared in quatro_solver.cpp.

namespace verifybench {

/// `quatro` (Lim, Lee, Myung, ICRA 2022); its yaw GNC takes the gnc-* settings.
struct QuatroParams {
  /// COTE on the rotation inliers only (the authors' using_rot_inliers_when_estimating_cote;
  /// false there: on the whole max clique).
  bool cote_rotation_inliers = false;
};

}  // namespace verifybench
