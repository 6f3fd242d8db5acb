#include "loop/relations.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"

namespace verifybench {

namespace {

constexpr const char* kFields[] = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};

/// The logged odometry at t, interpolated between the samples around it (translation linearly,
/// rotation by slerp); nullopt outside the samples' span.
std::optional<Rigid<3>> odometry_at(const std::vector<double>& stamps,
                                    const std::vector<Rigid<3>>& poses, double t) {
  if (t < stamps.front() || t > stamps.back()) return std::nullopt;
  const auto hi = std::lower_bound(stamps.begin(), stamps.end(), t);
  const auto j = static_cast<std::size_t>(hi - stamps.begin());
  if (*hi == t || j == 0) return poses[j];
  const double span = stamps[j] - stamps[j - 1];
  const double f = span > 0 ? (t - stamps[j - 1]) / span : 0.0;
  const Eigen::Quaterniond a(poses[j - 1].linear()), b(poses[j].linear());
  Rigid<3> T = Rigid<3>::Identity();
  T.linear() = a.slerp(f, b).toRotationMatrix();
  T.translation() = (1 - f) * poses[j - 1].translation() + f * poses[j].translation();
  return T;
}

}  // namespace

std::vector<Relation> read_relations(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open (a relations file: t1 t2 x y z roll pitch yaw)");
  std::vector<Relation> out;
  std::string line;
  long long line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    std::istringstream words(line);
    double v[8];
    std::string token;
    for (int k = 0; k < 8; ++k) {
      if (!(words >> token)) {
        input_error(path, line_no, std::string("field ") + kFields[k] + " missing (" +
                                       std::to_string(k) + " of 8 fields: t1 t2 x y z roll pitch "
                                                           "yaw)");
      }
      const ParsedReal p = parse_real_token(token);
      if (p.error != NumberError::none) {
        input_error(path, line_no, std::string("field ") + kFields[k] + " = '" + token + "' is " +
                                       (p.error == NumberError::not_finite ? "not finite"
                                                                           : "not a number"));
      }
      v[k] = p.value;
    }
    if (words >> token) input_error(path, line_no, "more than 8 fields ('" + token + "')");
    if (v[1] < v[0]) {
      input_error(path, line_no, "t2 = " + std::to_string(v[1]) + " is before t1 = " +
                                     std::to_string(v[0]));
    }
    Relation r;
    r.t1 = v[0];
    r.t2 = v[1];
    r.T = Rigid<3>::Identity();
    r.T.linear() = (Eigen::AngleAxisd(v[7], Eigen::Vector3d::UnitZ()) *
                    Eigen::AngleAxisd(v[6], Eigen::Vector3d::UnitY()) *
                    Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitX()))
                       .toRotationMatrix();
    r.T.translation() = Eigen::Vector3d(v[2], v[3], v[4]);
    out.push_back(r);
  }
  if (out.empty()) input_error(path, 0, "no relation (t1 t2 x y z roll pitch yaw per line)");
  return out;
}

RelationError relation_error(const std::vector<Relation>& relations,
                             const std::vector<double>& frame_stamps,
                             const std::vector<Rigid<3>>& frame_poses,
                             const std::vector<double>& odometry_stamps,
                             const std::vector<Rigid<3>>& odometry) {
  if (frame_stamps.size() != frame_poses.size() || frame_stamps.empty()) {
    throw std::invalid_argument("relation_error: " + std::to_string(frame_stamps.size()) +
                                " frame stamps for " + std::to_string(frame_poses.size()) +
                                " poses (at least one of each)");
  }
  if (odometry_stamps.size() != odometry.size() || odometry.size() < 2) {
    throw std::invalid_argument("relation_error: " + std::to_string(odometry_stamps.size()) +
                                " odometry stamps for " + std::to_string(odometry.size()) +
                                " poses (at least 2 of each)");
  }
  // x(t) = x_k o(t_k)^-1 o(t), k the frame nearest t.
  auto pose_at = [&](double t) -> std::optional<Rigid<3>> {
    const auto o_t = odometry_at(odometry_stamps, odometry, t);
    if (!o_t) return std::nullopt;
    auto it = std::lower_bound(frame_stamps.begin(), frame_stamps.end(), t);
    std::size_t k = static_cast<std::size_t>(it - frame_stamps.begin());
    if (k == frame_stamps.size() || (k > 0 && t - frame_stamps[k - 1] < frame_stamps[k] - t)) --k;
    const auto o_k = odometry_at(odometry_stamps, odometry, frame_stamps[k]);
    if (!o_k) return std::nullopt;
    return Rigid<3>(frame_poses[k] * o_k->inverse() * *o_t);
  };
  RelationError e;
  e.relations = static_cast<int>(relations.size());
  double t_sum = 0, t_sq = 0, r_sum = 0, r_sq = 0;
  for (const Relation& r : relations) {
    const auto a = pose_at(r.t1), b = pose_at(r.t2);
    if (!a || !b) continue;
    const Rigid<3> error = r.T.inverse() * (a->inverse() * *b);  // delta*^-1 delta
    const double t = error.translation().norm();
    const double angle =
        Eigen::AngleAxisd(Eigen::Matrix3d(error.linear())).angle() * 180.0 / M_PI;
    t_sum += t;
    t_sq += t * t;
    r_sum += angle;
    r_sq += angle * angle;
    ++e.used;
  }
  if (e.used > 0) {
    e.translation_m = t_sum / e.used;
    e.translation_sq = t_sq / e.used;
    e.rotation_deg = r_sum / e.used;
    e.rotation_sq = r_sq / e.used;
  }
  return e;
}

}  // namespace verifybench
