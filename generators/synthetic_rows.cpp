// The generators' shape settings, one row each (synthetic.hpp): their options, report keys,
// Python keywords, ranges (those of SyntheticParams::validate) and help.
#include "generators/synthetic.hpp"

namespace verifybench {

namespace {

using Row = ParamRow<SyntheticParams>;
using K = Row::Kind;

Row row(std::string option, std::string value_name, std::string help, double min, double max,
        std::string expected) {
  Row r;
  r.key = option;
  for (char& c : r.key) {
    if (c == '-') c = '_';
  }
  r.option = std::move(option);
  r.value_name = std::move(value_name);
  r.help = std::move(help);
  r.kind = K::real;
  r.min = min;
  r.max = max;
  r.expected = std::move(expected);
  return r;
}

std::vector<Row> make_rows() {
  std::vector<Row> rows;
  Row planar = row("planar-motion", "",
                   "3D: true rotations are yaw about z only (ground vehicles; Quatro's regime), "
                   "not uniform on SO(3)",
                   0, 1, "");
  planar.kind = K::flag;
  rows.push_back(param_row(&SyntheticParams::planar_motion, planar));
  rows.push_back(param_row(&SyntheticParams::group_ratio,
                           row("group-ratio", "R", "rigid-group: wrong group size / inlier count",
                               1e-9, 1e9, "a finite value > 0")));
  rows.push_back(param_row(&SyntheticParams::grid_spacing,
                           row("grid-spacing", "M",
                               "repetitive: pillar spacing along the corridor [m]", 1e-9, 1e9,
                               "a value in (0, extent]")));
  rows.push_back(param_row(&SyntheticParams::overlap,
                           row("overlap", "F",
                               "partial-overlap: fraction of the scene holding the inliers", 1e-9,
                               1.0, "a value in (0, 1]")));
  rows.push_back(param_row(&SyntheticParams::tail_dof,
                           row("tail-dof", "NU", "heavy-tailed: Student-t degrees of freedom", 1e-9,
                               1e9, "a finite value > 0")));
  rows.push_back(param_row(&SyntheticParams::anisotropy,
                           row("anisotropy", "A",
                               "anisotropic: noise along the sensor ray / across it", 1.0, 1e9,
                               "a finite value >= 1")));
  rows.push_back(param_row(&SyntheticParams::near_radius,
                           row("near-radius", "M",
                               "near-true, bev-orb: outliers this far from the truth [m]", 1e-9,
                               1e9, "a finite value > 0")));
  rows.push_back(param_row(&SyntheticParams::cell,
                           row("cell", "M", "bev-orb: bird's-eye-view cell size [m]", 1e-9, 1e9,
                               "a finite value > 0")));
  rows.push_back(param_row(&SyntheticParams::score_separation,
                           row("score-separation", "D",
                               "match scores N(D * label, 1), inliers higher (prosac's order)",
                               -1e9, 1e9, "a finite value (< 0 = no scores)")));
  return rows;
}

}  // namespace

const std::vector<ParamRow<SyntheticParams>>& synthetic_shape_rows() {
  static const std::vector<Row> rows = make_rows();
  return rows;
}

}  // namespace verifybench
