#include "generators/odometry.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace verifybench {

void DriftParams::validate() const {
  for (auto [name, v] : {std::pair<const char*, double>{"trans_rel", trans_rel},
                         {"yaw_deg", yaw_deg},
                         {"tilt_deg", tilt_deg}}) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(std::string("drift: ") + name + " must be >= 0, got " +
                                  std::to_string(v));
    }
  }
}

Rigid<3> perturbation(const Eigen::Vector3d& w, const Eigen::Vector3d& v) {
  Rigid<3> E = Rigid<3>::Identity();
  const double angle = w.norm();
  if (angle > 0.0) E.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  E.translation() = v;
  return E;
}

std::vector<Rigid<3>> drift_odometry(const std::vector<Rigid<3>>& truth, const DriftParams& params,
                                     std::uint64_t seed) {
  params.validate();
  std::vector<Rigid<3>> odo;
  odo.reserve(truth.size());
  if (truth.empty()) return odo;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  const double deg = M_PI / 180.0;
  odo.push_back(truth.front());
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Rigid<3> D = truth[i - 1].inverse() * truth[i];
    const double s = D.translation().norm();
    Eigen::Vector3d w, v;
    for (int k = 0; k < 3; ++k) v(k) = params.trans_rel * s * n01(rng);
    w.x() = params.tilt_deg * deg * std::sqrt(s) * n01(rng);
    w.y() = params.tilt_deg * deg * std::sqrt(s) * n01(rng);
    w.z() = params.yaw_deg * deg * std::sqrt(s) * n01(rng);
    Rigid<3> next = odo.back() * D * perturbation(w, v);
    next.linear() = Eigen::Quaterniond(next.linear()).normalized().toRotationMatrix();
    odo.push_back(next);
  }
  return odo;
}

}  // namespace verifybench
