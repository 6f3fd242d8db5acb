#include "acceptance/dense_check.hpp"

#include <algorithm>
#include <array>
#include <unordered_map>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/timer.hpp"

namespace verifybench {

void DenseCheckParams::validate() const {
  if (!(min_overlap == kRuleDefault || (min_overlap >= 0.0 && min_overlap < 1.0))) {
    throw std::invalid_argument("dense check: min_overlap must be in [0, 1) or -1 (the rule's "
                                "default), got " + std::to_string(min_overlap));
  }
  if (!(cell > 0.0) || !std::isfinite(cell)) {
    throw std::invalid_argument("dense check: cell must be positive, got " + std::to_string(cell));
  }
  icp.validate();
}

namespace {

using Cell = std::array<long long, 3>;

struct CellHash {
  std::size_t operator()(const Cell& c) const {
    return static_cast<std::size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
  }
};

Cell cell_of(const Eigen::Vector3d& p, double cell) {
  return {static_cast<long long>(std::floor(p.x() / cell)),
          static_cast<long long>(std::floor(p.y() / cell)),
          static_cast<long long>(std::floor(p.z() / cell))};
}

// One centroid per occupied cell: both maps at the same density whatever their voxels.
std::vector<Eigen::Vector3d> centroids(const std::vector<Eigen::Vector3f>& points,
                                       const Rigid<3>& T, double cell) {
  std::unordered_map<Cell, std::pair<Eigen::Vector3d, int>, CellHash> sums;
  for (const auto& p : points) {
    const Eigen::Vector3d q = T * p.cast<double>();
    auto& s = sums.try_emplace(cell_of(q, cell), Eigen::Vector3d::Zero(), 0).first->second;
    s.first += q;
    ++s.second;
  }
  std::vector<std::pair<Cell, Eigen::Vector3d>> ordered;  // in cell order: no hash-order effects
  for (const auto& [c, s] : sums) ordered.emplace_back(c, s.first / s.second);
  std::sort(ordered.begin(), ordered.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Eigen::Vector3d> out;
  for (const auto& [c, p] : ordered) out.push_back(p);
  return out;
}

// The share of `a`'s points with a point of `b` within `radius` (a grid of radius-sized cells).
double covered(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
               double radius) {
  if (a.empty() || b.empty()) return 0.0;
  std::unordered_map<Cell, std::vector<int>, CellHash> grid;
  for (int i = 0; i < static_cast<int>(b.size()); ++i) grid[cell_of(b[i], radius)].push_back(i);
  const double r2 = radius * radius;
  std::size_t hits = 0;
  for (const auto& p : a) {
    const Cell c = cell_of(p, radius);
    bool hit = false;
    for (int dx = -1; dx <= 1 && !hit; ++dx) {
      for (int dy = -1; dy <= 1 && !hit; ++dy) {
        for (int dz = -1; dz <= 1 && !hit; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (int j : it->second) {
            if ((b[j] - p).squaredNorm() <= r2) {
              hit = true;
              break;
            }
          }
        }
      }
    }
    hits += hit;
  }
  return static_cast<double>(hits) / static_cast<double>(a.size());
}

}  // namespace

DenseCheck dense_check(const Cloud& source, const Cloud& target, const Rigid<3>& T_target_source,
                       const DenseCheckParams& params) {
  StopWatch clock;
  DenseCheck out;
  out.ran = true;
  out.icp = refine_icp(source, target, T_target_source, params.icp);
  const auto q = centroids(source, out.icp.T_target_source, params.cell);
  const auto m = centroids(target, Rigid<3>::Identity(), params.cell);
  // Of the smaller map, the share that the other one covers within a cell.
  out.overlap = q.size() <= m.size() ? covered(q, m, params.cell) : covered(m, q, params.cell);
  out.ms = clock.ms();
  return out;
}

const std::vector<ParamRow<DenseCheckParams>>& dense_check_param_rows() {
  using P = DenseCheckParams;
  auto nested = [](double RefineParams::*member, std::string option, std::string key,
                   std::string help) {
    ParamRow<P> row;
    row.option = std::move(option);
    row.key = std::move(key);
    row.value_name = "M";
    row.help = std::move(help);
    row.min = 1e-3;
    row.max = 1e3;
    row.expected = "a value in [0.001, 1000]";
    return param_row(&P::icp, member, row);
  };
  static const std::vector<ParamRow<P>> rows = {
      field_row(&P::min_overlap, "dense-overlap", "min_overlap", "F",
                "dense check of the pairs the accept rule accepted, where the clouds are known (the "
                "loop's maps, a dump's kept clouds): ICP from the fitted motion, then accept only "
                "when their occupied cells overlap by more than F of the smaller one (0 = off, "
                "the paper's setting; -1 = the rule's default: under --accept pvalue 0.56 for the "
                "loop's maps, 0.4 for a dump's scans; off under count)",
                -1.0, 0.999, "a value in [0, 0.999], or -1 (the rule's default)"),
      field_row(&P::cell, "dense-cell", "cell_m", "M", "dense check: overlap cell size", 1e-3, 1e3,
                "a value in [0.001, 1000]"),
      nested(&RefineParams::voxel, "dense-icp-voxel", "icp_voxel_m",
             "dense check: both clouds voxelised for ICP"),
      nested(&RefineParams::max_correspondence, "dense-icp-distance", "icp_max_distance_m",
             "dense check: ICP correspondence distance")};
  return rows;
}

}  // namespace verifybench
