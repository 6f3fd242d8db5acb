#include "loop/local_maps.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace verifybench {

void LocalMapParams::validate() const {
  for (auto [name, v] : {std::pair<const char*, double>{"map_length", map_length},
                         {"voxel", voxel},
                         {"occupancy_voxel", occupancy_voxel}}) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(std::string("local maps: ") + name +
                                  " must be a positive number, got " + std::to_string(v));
    }
  }
}

std::vector<std::vector<int>> partition_maps(const std::vector<Rigid<3>>& odometry,
                                             const std::vector<int>& frames, double map_length) {
  std::vector<std::vector<int>> maps;
  double travelled = 0.0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (maps.empty() || travelled >= map_length) {
      maps.emplace_back();
      travelled = 0.0;
    }
    if (!maps.back().empty()) {
      travelled += (odometry[frames[k]].translation() -
                    odometry[maps.back().back()].translation()).norm();
    }
    maps.back().push_back(frames[k]);
  }
  return maps;
}

double map_travel(const std::vector<LocalMap>& maps, int i, int j) {
  double length = 0.0;
  for (int k = std::min(i, j); k < std::max(i, j); ++k) {
    length += (maps[k + 1].T_world_map_odometry.translation() -
               maps[k].T_world_map_odometry.translation())
                  .norm();
  }
  return length;
}

std::uint64_t voxel_key(const Eigen::Vector3d& p, double voxel) {
  constexpr long long kHalf = 1LL << 20;
  std::uint64_t key = 0;
  for (int k = 0; k < 3; ++k) {
    long long c = static_cast<long long>(std::floor(std::clamp(p(k) / voxel, -1e12, 1e12)));
    c = std::clamp(c, -kHalf, kHalf - 1) + kHalf;
    key = (key << 21) | static_cast<std::uint64_t>(c);
  }
  return key;
}

double overlap_ratio(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
  if (a.empty() || b.empty()) return 0.0;
  std::size_t i = 0, j = 0, common = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i] < b[j]) {
      ++i;
    } else if (b[j] < a[i]) {
      ++j;
    } else {
      ++common, ++i, ++j;
    }
  }
  return static_cast<double>(common) / static_cast<double>(std::min(a.size(), b.size()));
}

LocalMap build_local_map(int index, const std::vector<int>& frames,
                         const std::vector<Rigid<3>>& odometry, const std::vector<Rigid<3>>& truth,
                         const ScanSource& scans, const LocalMapParams& params) {
  params.validate();
  if (frames.empty()) throw std::invalid_argument("local map " + std::to_string(index) + ": no frame");
  LocalMap map;
  map.index = index;
  map.frames = frames;
  map.anchor = frames[frames.size() / 2];
  map.T_world_map_odometry = odometry[map.anchor];
  map.T_world_map_truth = truth[map.anchor];
  struct Sum {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    int n = 0;
  };
  std::unordered_map<std::uint64_t, Sum> cells;
  std::vector<std::uint64_t> occupancy;
  const Rigid<3> T_map_world = map.T_world_map_odometry.inverse();
  for (int f : frames) {
    const Rigid<3> T_map_scan = T_map_world * odometry[f];
    const Rigid<3>& T_world_scan = truth[f];
    for (const Eigen::Vector3f& q : scans(f)) {
      const Eigen::Vector3d p = q.cast<double>();
      Sum& s = cells[voxel_key(T_map_scan * p, params.voxel)];
      s.p += T_map_scan * p;
      ++s.n;
      occupancy.push_back(voxel_key(T_world_scan * p, params.occupancy_voxel));
    }
  }
  // Centroids in key order, so the map does not depend on the hash table's layout.
  std::vector<std::pair<std::uint64_t, Eigen::Vector3f>> ordered;
  ordered.reserve(cells.size());
  for (const auto& [key, s] : cells) ordered.emplace_back(key, (s.p / s.n).cast<float>());
  std::sort(ordered.begin(), ordered.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  map.points.reserve(ordered.size());
  for (const auto& [key, p] : ordered) map.points.push_back(p);
  std::sort(occupancy.begin(), occupancy.end());
  occupancy.erase(std::unique(occupancy.begin(), occupancy.end()), occupancy.end());
  map.occupancy = std::move(occupancy);
  return map;
}

const std::vector<ParamRow<LocalMapParams>>& local_map_param_rows() {
  using P = LocalMapParams;
  static const std::vector<ParamRow<P>> rows = {
      field_row(&P::map_length, "map-length", "map_length_m", "M",
                "odometry travel per local map [m]", 1.0, 1e6, "a value in [1, 1e6]"),
      field_row(&P::voxel, "map-voxel", "map_voxel_m", "M", "local map voxel [m]", 0.01, 100.0,
                "a value in [0.01, 100]")};
  return rows;
}

}  // namespace verifybench
