#include "datasets/trajectory.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/transform.hpp"

namespace verifybench {
namespace {

std::vector<std::string> split(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> tokens;
  for (std::string t; in >> t;) tokens.push_back(t);
  return tokens;
}

constexpr const char* kTumFields[8] = {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};

// The first line that is neither blank nor a '#' comment, split; empty when there is none.
std::vector<std::string> first_pose_line(const std::string& path, long long& line_no) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    auto tokens = split(line);
    if (!tokens.empty() && tokens[0][0] != '#') return tokens;
  }
  return {};
}

}  // namespace

Rigid<3> parse_row_major_pose(const std::vector<std::string>& tokens, const std::string& path,
                              long long line, int first_field) {
  if (tokens.size() != 12) {
    input_error(path, line,
                std::to_string(tokens.size()) + " numbers; a pose is 12 (row-major 3x4)");
  }
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  for (int k = 0; k < 12; ++k) {
    const ParsedReal x = parse_real_token(tokens[k]);
    if (x.error != NumberError::none) {
      input_error(path, line,
                  "field " + std::to_string(k + first_field) + " '" + tokens[k] +
                      "' is not a finite number");
    }
    M(k / 4, k % 4) = x.value;
  }
  return published_rigid<3>(M, path + ":" + std::to_string(line)).T;
}

Trajectory read_kitti_poses(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  Trajectory poses;
  long long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto tokens = split(line);
    if (tokens.empty()) continue;
    poses.push_back(parse_row_major_pose(tokens, path, line_no));
  }
  if (poses.empty()) input_error(path, 0, "no pose (one row-major 3x4 a line expected)");
  return poses;
}

Rigid<3> read_kitti_calib_tr(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  long long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    auto tokens = split(line);
    if (tokens.empty() || tokens[0] != "Tr:") continue;
    tokens.erase(tokens.begin());
    return parse_row_major_pose(tokens, path, line_no);
  }
  input_error(path, 0, "no 'Tr:' line (T_camera_velodyne, 12 numbers)");
}

Trajectory camera_to_velodyne(const Trajectory& camera_poses, const Rigid<3>& Tr) {
  Trajectory out;
  out.reserve(camera_poses.size());
  const Rigid<3> Tr_inv = Tr.inverse();
  for (const auto& P : camera_poses) out.push_back(Tr_inv * P * Tr);
  return out;
}

void write_kitti_poses(const std::string& path, const Trajectory& poses) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out.precision(9);
  for (const auto& T : poses) {
    const Eigen::Matrix4d M = T.matrix();
    for (int k = 0; k < 12; ++k) out << (k ? " " : "") << M(k / 4, k % 4);
    out << "\n";
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

StampedTrajectory read_tum_poses(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  StampedTrajectory out;
  long long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto tokens = split(line);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    if (tokens.size() != 8) {
      input_error(path, line_no,
                  std::to_string(tokens.size()) +
                      " fields; a TUM pose is 8 (timestamp tx ty tz qx qy qz qw)");
    }
    double v[8];
    for (int k = 0; k < 8; ++k) {
      const ParsedReal x = parse_real_token(tokens[k]);
      if (x.error != NumberError::none) {
        input_error(path, line_no,
                    "field " + std::to_string(k + 1) + " (" + kTumFields[k] + ") '" + tokens[k] +
                        "' is not a finite number");
      }
      v[k] = x.value;
    }
    if (!out.stamps.empty() && !(v[0] > out.stamps.back())) {
      input_error(path, line_no,
                  "field 1 (timestamp) '" + tokens[0] + "' is not after the previous pose's");
    }
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);  // Eigen takes w first
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      input_error(path, line_no,
                  "quaternion (qx qy qz qw) = (" + tokens[4] + " " + tokens[5] + " " + tokens[6] +
                      " " + tokens[7] + ") has norm " + std::to_string(q.norm()) +
                      "; a rotation's is 1 (within 1e-3)");
    }
    Rigid<3> T = Rigid<3>::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() << v[1], v[2], v[3];
    out.stamps.push_back(v[0]);
    out.poses.push_back(T);
  }
  if (out.poses.empty()) input_error(path, 0, "no pose (timestamp tx ty tz qx qy qz qw a line)");
  return out;
}

void write_tum_poses(const std::string& path, const std::vector<double>& stamps,
                     const Trajectory& poses) {
  if (stamps.size() != poses.size()) {
    throw std::invalid_argument(path + ": " + std::to_string(stamps.size()) + " stamps for " +
                                std::to_string(poses.size()) + " poses");
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  char line[256];
  for (std::size_t i = 0; i < poses.size(); ++i) {
    Eigen::Quaterniond q(poses[i].linear());
    q.normalize();
    if (q.w() < 0) q.coeffs() = -q.coeffs();  // one of the two signs, for stable files
    const Eigen::Vector3d t = poses[i].translation();
    std::snprintf(line, sizeof line, "%.9f %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", stamps[i], t.x(),
                  t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
    out << line;
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

StampedTrajectory read_poses_file(const std::string& path) {
  long long line_no = 0;
  const auto tokens = first_pose_line(path, line_no);
  if (tokens.size() == 8) return read_tum_poses(path);
  if (tokens.size() == 12) return {{}, read_kitti_poses(path)};
  if (tokens.empty()) input_error(path, 0, "no pose line");
  input_error(path, line_no,
              std::to_string(tokens.size()) +
                  " fields; a pose line is 8 (TUM: timestamp tx ty tz qx qy qz qw) or 12 (KITTI: "
                  "row-major 3x4)");
}

std::vector<double> path_length(const Trajectory& poses) {
  std::vector<double> s(poses.size(), 0.0);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    s[i] = s[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();
  }
  return s;
}

}  // namespace verifybench
