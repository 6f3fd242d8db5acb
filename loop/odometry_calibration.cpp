#include "loop/odometry_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "frontend/extract.hpp"

namespace verifybench {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMinPairs = 10;  ///< matched and kept pairs a rate needs

double wrap_angle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

double planar_yaw(const Eigen::Matrix2d& R) { return std::atan2(R(1, 0), R(0, 0)); }

/// Target points hashed by cell of side `cell`: nearest neighbour within `cell` by the 3 x 3 cells
/// around a query.
class PlanarGrid {
 public:
  PlanarGrid(const std::vector<Eigen::Vector2d>& points, double cell) : points_(points), cell_(cell) {
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
      cells_[key(cell_of(points[i].x()), cell_of(points[i].y()))].push_back(i);
    }
  }
  /// Index of the nearest point within `cell` of p, or -1.
  int nearest(const Eigen::Vector2d& p) const {
    const std::int64_t cx = cell_of(p.x()), cy = cell_of(p.y());
    int best = -1;
    double best_d2 = cell_ * cell_;
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (int i : it->second) {
          const double d2 = (points_[i] - p).squaredNorm();
          if (d2 < best_d2) {
            best_d2 = d2;
            best = i;
          }
        }
      }
    }
    return best;
  }
  /// Indices of the points within `cell` of p.
  std::vector<int> within(const Eigen::Vector2d& p) const {
    std::vector<int> out;
    const std::int64_t cx = cell_of(p.x()), cy = cell_of(p.y());
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (int i : it->second) {
          if ((points_[i] - p).squaredNorm() <= cell_ * cell_) out.push_back(i);
        }
      }
    }
    return out;
  }

 private:
  std::int64_t cell_of(double v) const { return static_cast<std::int64_t>(std::floor(v / cell_)); }
  static std::int64_t key(std::int64_t x, std::int64_t y) {
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(x) << 32) ^
                                     static_cast<std::uint32_t>(y));
  }
  const std::vector<Eigen::Vector2d>& points_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

std::vector<Eigen::Vector2d> planar_points(const std::vector<Eigen::Vector3f>& cloud,
                                           const std::string& which) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(cloud.size());
  for (const Eigen::Vector3f& p : cloud) {
    if (!(std::abs(p.z()) <= 1e-6f)) {
      throw std::invalid_argument(
          "--odometry-calibration needs planar scans (a 2D laser log); " + which +
          " has a point at z = " + std::to_string(p.z()));
    }
    out.emplace_back(p.x(), p.y());
  }
  return out;
}

double median(std::vector<double> v) {
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  double m = v[mid];
  if (v.size() % 2 == 0) {
    m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid)));
  }
  return m;
}

/// Each target point's line normal: the direction of least spread of the target points within
/// `radius` (at least 3 of them, their variance along the line at least 10 times that across
/// it); zero where the neighbourhood is no line.
std::vector<Eigen::Vector2d> line_normals(const std::vector<Eigen::Vector2d>& target,
                                          double radius) {
  std::vector<Eigen::Vector2d> normals(target.size(), Eigen::Vector2d::Zero());
  const PlanarGrid grid(target, radius);
  for (std::size_t j = 0; j < target.size(); ++j) {
    std::vector<int> near = grid.within(target[j]);
    if (near.size() < 3) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (int i : near) mean += target[i];
    mean /= static_cast<double>(near.size());
    Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
    for (int i : near) C += (target[i] - mean) * (target[i] - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(C);
    if (!(eig.eigenvalues()(1) > 10.0 * eig.eigenvalues()(0))) continue;
    normals[j] = eig.eigenvectors().col(0);
  }
  return normals;
}

/// Point-to-line ICP (Censi 2008's metric, solved by Gauss-Newton in SE(2)): each source point
/// moved by T pairs with its nearest target point q_j within the pairing distance, and the
/// residual is its distance to q_j's line, n_j . (T p - q_j); a step (dtheta, dx, dy) applied
/// on the left minimises the sum of squares to first order.
PlanarIcp icp_2d(const std::vector<Eigen::Vector2d>& source,
                 const std::vector<Eigen::Vector2d>& target, const Rigid<2>& T0,
                 const OdometryCalibrationParams& params) {
  PlanarIcp out;
  out.T = T0;
  if (source.size() < 3 || target.size() < 3) return out;
  const std::vector<Eigen::Vector2d> normals = line_normals(target, params.max_distance);
  // Coarse then fine: the first third of the iterations pair points within twice the distance.
  const int coarse = params.max_iterations / 3;
  const PlanarGrid wide(target, 2.0 * params.max_distance);
  const PlanarGrid fine(target, params.max_distance);
  int paired = 0;
  for (int it = 0; it < params.max_iterations; ++it) {
    const PlanarGrid& grid = it < coarse ? wide : fine;
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    paired = 0;
    for (const Eigen::Vector2d& p : source) {
      const Eigen::Vector2d moved = out.T * p;
      const int j = grid.nearest(moved);
      if (j < 0) continue;
      ++paired;
      const Eigen::Vector2d& n = normals[j];
      if (n.isZero()) continue;
      const Eigen::Vector3d J(n.dot(Eigen::Vector2d(-moved.y(), moved.x())), n.x(), n.y());
      const double r = n.dot(moved - target[j]);
      H += J * J.transpose();
      g += J * r;
    }
    if (paired < 3 || !(H.trace() > 0.0)) return out;
    // A faint damping keeps a direction the scene does not pin (along a corridor) where it is.
    const Eigen::Vector3d delta =
        -(H + 1e-6 * H.trace() * Eigen::Matrix3d::Identity()).ldlt().solve(g);
    if (!delta.allFinite()) return out;
    Rigid<2> step = Rigid<2>::Identity();
    step.linear() = Eigen::Rotation2Dd(delta(0)).toRotationMatrix();
    step.translation() = delta.tail<2>();
    out.T = step * out.T;
    if (it >= coarse && delta.norm() < 1e-7) {
      out.converged = true;
      break;
    }
  }
  // The share is counted at the fine distance (the last iteration's pairing).
  out.matched_share = static_cast<double>(paired) / static_cast<double>(source.size());
  return out;
}

}  // namespace

void OdometryCalibrationParams::validate() const {
  if (!(max_distance > 0.0 && std::isfinite(max_distance))) {
    throw std::invalid_argument("odometry calibration: max_distance must be > 0, got " +
                                std::to_string(max_distance));
  }
  if (max_iterations < 3) {
    throw std::invalid_argument("odometry calibration: max_iterations must be >= 3, got " +
                                std::to_string(max_iterations));
  }
  if (!(min_matched_share > 0.0 && min_matched_share <= 1.0)) {
    throw std::invalid_argument("odometry calibration: min_matched_share must be in (0, 1], got " +
                                std::to_string(min_matched_share));
  }
}

const std::vector<ParamRow<OdometryCalibrationParams>>& odometry_calibration_param_rows() {
  using P = OdometryCalibrationParams;
  static const std::vector<ParamRow<P>> rows = {
      field_row(&P::enabled, "odometry-calibration", "odometry_calibration", "",
                "2D laser logs: measure the odometry's constant heading drift per metre (unequal "
                "wheels) by ICP of consecutive scans and take it out before the maps; the heading "
                "noise left replaces --drift-yaw-deg"),
      field_row(&P::max_distance, "calibration-max-distance", "calibration_max_distance_m", "M",
                "odometry calibration: ICP pairs points closer than M (2 M at first)", 1e-3, 100.0,
                "a value in [0.001, 100]"),
      field_row(&P::min_matched_share, "calibration-min-share", "calibration_min_share", "F",
                "odometry calibration: a scan pair counts when ICP pairs at least this share of "
                "its points",
                1e-3, 1.0, "a value in [0.001, 1]")};
  return rows;
}

PlanarIcp planar_icp(const std::vector<Eigen::Vector3f>& source,
                     const std::vector<Eigen::Vector3f>& target, const Rigid<2>& T0,
                     const OdometryCalibrationParams& params) {
  params.validate();
  return icp_2d(planar_points(source, "the source scan"), planar_points(target, "the target scan"),
                T0, params);
}

OdometryCalibration calibrate_odometry(const std::vector<int>& frames, const ScanSource& scans,
                                       const OdometryCalibrationParams& params,
                                       Trajectory& odometry) {
  params.validate();
  OdometryCalibration cal;
  cal.ran = true;
  // Steps 1-2: each consecutive pair's heading error and travel.
  std::vector<Rigid<3>> steps;  // O_i, from the odometry as it came
  std::vector<double> travel, error, matched_travel;
  auto frame_name = [](int f) { return "frame " + std::to_string(f); };
  std::vector<Eigen::Vector2d> target = planar_points(scans(frames[0]), frame_name(frames[0]));
  for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
    const Rigid<3> O = odometry.at(frames[k]).inverse() * odometry.at(frames[k + 1]);
    steps.push_back(O);
    const Rigid<2> O2 = planar(O);
    const double L = O2.translation().norm();
    travel.push_back(L);
    std::vector<Eigen::Vector2d> source =
        planar_points(scans(frames[k + 1]), frame_name(frames[k + 1]));
    if (L > 1e-3) {
      ++cal.pairs;
      const PlanarIcp icp = icp_2d(source, target, O2, params);
      if (icp.converged && icp.matched_share >= params.min_matched_share) {
        error.push_back(wrap_angle(planar_yaw(icp.T.linear()) - planar_yaw(O2.linear())));
        matched_travel.push_back(L);
      }
    }
    target = std::move(source);
  }
  cal.matched = static_cast<int>(error.size());
  auto too_few = [&](int count, const std::string& what) {
    if (count >= kMinPairs) return;
    throw std::invalid_argument(
        "--odometry-calibration: " + what + " " + std::to_string(count) + " of " +
        std::to_string(cal.pairs) + " consecutive scan pairs; at least " +
        std::to_string(kMinPairs) +
        " are needed (more scans, or a larger --calibration-max-distance or smaller "
        "--calibration-min-share)");
  };
  too_few(cal.matched, "ICP matched");
  // Step 3: b0 from the median rate, the MAD trim, then b = sum e / sum L over the rest.
  std::vector<double> rate(error.size());
  for (std::size_t i = 0; i < error.size(); ++i) rate[i] = error[i] / matched_travel[i];
  const double b0 = median(rate);
  std::vector<double> residual(error.size());
  for (std::size_t i = 0; i < error.size(); ++i) residual[i] = error[i] - b0 * matched_travel[i];
  const double centre = median(residual);
  std::vector<double> spread(residual.size());
  for (std::size_t i = 0; i < residual.size(); ++i) spread[i] = std::abs(residual[i] - centre);
  const double bound = 3.0 * 1.4826 * median(spread) + 1e-12;
  double sum_e = 0.0, sum_l = 0.0;
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < error.size(); ++i) {
    if (std::abs(residual[i] - centre) > bound) continue;
    kept.push_back(i);
    sum_e += error[i];
    sum_l += matched_travel[i];
  }
  too_few(static_cast<int>(kept.size()), "the trim kept");
  const double b = sum_e / sum_l;
  double sq = 0.0;
  for (std::size_t i : kept) sq += std::pow(error[i] - b * matched_travel[i], 2);
  cal.kept = static_cast<int>(kept.size());
  cal.travel_m = sum_l;
  cal.yaw_rate_deg_per_m = b * 180.0 / kPi;
  cal.residual_deg_rms = kept.empty() ? 0.0 : std::sqrt(sq / kept.size()) * 180.0 / kPi;
  cal.yaw_sigma_deg_per_sqrt_m = sum_l > 0.0 ? std::sqrt(sq / sum_l) * 180.0 / kPi : 0.0;
  // Step 4: recompose, each step's heading change corrected by b L_i.
  Rigid<3> pose = odometry.at(frames[0]);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    Rigid<3> correction = Rigid<3>::Identity();
    correction.linear() =
        Eigen::AngleAxisd(b * travel[k], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose = pose * steps[k] * correction;
    odometry.at(frames[k + 1]) = pose;
  }
  return cal;
}

}  // namespace verifybench
