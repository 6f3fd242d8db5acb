// The generators' shape settings, one row each (synthetic.hpp): their options, report keys,
// Python keywords, ranges (those of SyntheticParams::validate) and help.
#include "generators/synthetic.hpp"

namespace verifybench {

namespace {

// The option with '-' as '_' is the report key and the Python keyword.
std::vector<ParamRow<SyntheticParams>> make_rows() {
  using P = SyntheticParams;
  return {
      field_row(&P::planar_motion, "planar-motion", "planar_motion", "",
                "3D: true rotations are yaw about z only (ground vehicles; Quatro's regime), not "
                "uniform on SO(3)"),
      field_row(&P::group_ratio, "group-ratio", "group_ratio", "R",
                "rigid-group: wrong group size / inlier count", 1e-9, 1e9, "a finite value > 0"),
      field_row(&P::grid_spacing, "grid-spacing", "grid_spacing", "M",
                "repetitive: pillar spacing along the corridor [m]", 1e-9, 1e9,
                "a value in (0, extent]"),
      field_row(&P::overlap, "overlap", "overlap", "F",
                "partial-overlap: fraction of the scene holding the inliers", 1e-9, 1.0,
                "a value in (0, 1]"),
      field_row(&P::tail_dof, "tail-dof", "tail_dof", "NU",
                "heavy-tailed: Student-t degrees of freedom", 1e-9, 1e9, "a finite value > 0"),
      field_row(&P::anisotropy, "anisotropy", "anisotropy", "A",
                "anisotropic: noise along the sensor ray / across it", 1.0, 1e9,
                "a finite value >= 1"),
      field_row(&P::near_radius, "near-radius", "near_radius", "M",
                "near-true, bev-orb: outliers this far from the truth [m]", 1e-9, 1e9,
                "a finite value > 0"),
      field_row(&P::cell, "cell", "cell", "M", "bev-orb: bird's-eye-view cell size [m]", 1e-9,
                1e9, "a finite value > 0"),
      field_row(&P::score_separation, "score-separation", "score_separation", "D",
                "match scores N(D * label, 1), inliers higher (prosac's order)", -1e9, 1e9,
                "a finite value (< 0 = no scores)")};
}

}  // namespace

const std::vector<ParamRow<SyntheticParams>>& synthetic_shape_rows() {
  static const std::vector<ParamRow<SyntheticParams>> rows = make_rows();
  return rows;
}

}  // namespace verifybench
