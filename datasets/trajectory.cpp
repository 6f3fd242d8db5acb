#include "datasets/trajectory.hpp"

#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/transform.hpp"

namespace verifybench {
namespace {

// Twelve finite numbers from `tokens`, as a 4x4 pose checked by published_rigid.
Rigid<3> pose_from_tokens(const std::vector<std::string>& tokens, const std::string& path,
                          long long line) {
  if (tokens.size() != 12) {
    input_error(path, line,
                std::to_string(tokens.size()) + " numbers; a pose is 12 (row-major 3x4)");
  }
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  for (int k = 0; k < 12; ++k) {
    const ParsedReal x = parse_real_token(tokens[k]);
    if (x.error != NumberError::none) {
      input_error(path, line,
                  "field " + std::to_string(k + 1) + " '" + tokens[k] + "' is not a finite number");
    }
    M(k / 4, k % 4) = x.value;
  }
  return published_rigid<3>(M, path + ":" + std::to_string(line)).T;
}

std::vector<std::string> split(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> tokens;
  for (std::string t; in >> t;) tokens.push_back(t);
  return tokens;
}

}  // namespace

Trajectory read_kitti_poses(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  Trajectory poses;
  long long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto tokens = split(line);
    if (tokens.empty()) continue;
    poses.push_back(pose_from_tokens(tokens, path, line_no));
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
    return pose_from_tokens(tokens, path, line_no);
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

std::vector<double> path_length(const Trajectory& poses) {
  std::vector<double> s(poses.size(), 0.0);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    s[i] = s[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();
  }
  return s;
}

}  // namespace verifybench
