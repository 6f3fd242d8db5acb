#pragma once
// Local maps (the paper's Sec. III): scans are gathered into a map until the odometry has
// travelled map_length metres; each map lives in the frame of its middle scan (its anchor), built
// with the odometry (so the drift inside a map is in it, as on a robot), and voxelised to one
// centroid per voxel. Beside the points each map keeps its ground-truth occupancy: the keys of the
// occupancy_voxel cells its scans hit, placed with the true poses, for the ground-truth closures.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/correspondences.hpp"
#include "core/param_rows.hpp"

namespace verifybench {

struct LocalMapParams {
  double map_length = 100.0;      ///< [m] odometry travel per map
  double voxel = 0.5;             ///< [m] map voxel (centroids)
  double occupancy_voxel = 0.5;   ///< [m] ground-truth occupancy cells
  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// The local maps' settings a user sets (`loop --map-length`, `--map-voxel`), as rows.
const std::vector<ParamRow<LocalMapParams>>& local_map_param_rows();

struct LocalMap {
  int index = 0;
  std::vector<int> frames;  ///< trajectory frame indices of its scans, ascending
  int anchor = 0;           ///< the middle of frames; the map's frame
  Rigid<3> T_world_map_odometry = Rigid<3>::Identity();
  Rigid<3> T_world_map_truth = Rigid<3>::Identity();
  std::vector<Eigen::Vector3f> points;   ///< voxel centroids, map frame
  std::vector<std::uint64_t> occupancy;  ///< sorted, unique cell keys (world frame, true poses)
};

/// Splits `frames` (ascending trajectory indices) into maps by odometry travel: a map closes when
/// the path from its first frame reaches map_length. The last, shorter map is kept.
std::vector<std::vector<int>> partition_maps(const std::vector<Rigid<3>>& odometry,
                                             const std::vector<int>& frames, double map_length);

/// One scan in its sensor frame, for a trajectory frame index.
using ScanSource = std::function<std::vector<Eigen::Vector3f>(int frame)>;

/// Builds map `index` from its frames.
LocalMap build_local_map(int index, const std::vector<int>& frames,
                         const std::vector<Rigid<3>>& odometry, const std::vector<Rigid<3>>& truth,
                         const ScanSource& scans, const LocalMapParams& params);

/// Odometry's travel between maps i and j (either order): the path of their anchors, map by map.
double map_travel(const std::vector<LocalMap>& maps, int i, int j);

/// Key of the cell of `p` at `voxel` (21 bits an axis, offset; beyond +-2^20 cells clamped).
std::uint64_t voxel_key(const Eigen::Vector3d& p, double voxel);

/// |A n B| / min(|A|, |B|) of two sorted key sets (0 when one is empty).
double overlap_ratio(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b);

}  // namespace verifybench
