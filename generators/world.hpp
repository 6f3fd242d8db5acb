#pragma once
// A seeded street world along a trajectory, for loop-closure runs without recorded scans (issue
// #14). The scene is one triangle mesh, built once for the whole path, so a revisit sees exactly
// what the first pass saw:
//   ground   a height field (cells of ground_cell) at the nearest path sample's height minus the
//            sensor height;
//   road     no object within road_half_width of the path;
//   kerb     in the band road_half_width .. + kerb_band: poles (some with a lamp arm), trees
//            (trunk + octahedral crown), parked cars (body + cabin, aligned with the road),
//            clutter;
//   blocks   from building_setback to building_depth: buildings (boxes aligned with the road,
//            some with a storey set back on top, some with a bay on the facade).
// Each placement cell of a grid of `cell` metres draws from its own seed
// derive_seed(seed, {cell x, cell y}), so the world does not depend on the path's order.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>

#include "core/param_rows.hpp"
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

struct Mesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;  ///< indices into vertices, counter-clockwise

  /// A box of half sizes `half` turned by `yaw` about z, its base centre at `base`.
  void add_box(const Eigen::Vector3d& base, const Eigen::Vector3d& half, double yaw);
  /// An octahedron of radii `half` centred at `centre`.
  void add_octahedron(const Eigen::Vector3d& centre, const Eigen::Vector3d& half);
};

struct WorldParams {
  double road_half_width = 5.0;   ///< [m] no object closer to the path
  double kerb_band = 3.0;         ///< [m] street furniture beyond the road
  double building_setback = 9.0;  ///< [m] nearest facade to the path
  double building_depth = 35.0;   ///< [m] no building centre beyond this
  double cell = 4.0;              ///< [m] placement grid
  double kerb_density = 0.45;     ///< chance of an object in a kerb cell
  double building_density = 0.2;  ///< chance of a building in a block cell
  double margin = 60.0;           ///< [m] ground beyond the path's bounding box
  double ground_cell = 10.0;      ///< [m] ground height field
  double sensor_height = 1.73;    ///< [m] sensor above the ground (KITTI's HDL-64)
  std::uint64_t seed = 1;

  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// The world's settings a user sets (`loop --world-*`), as rows (core/param_rows.hpp).
const std::vector<ParamRow<WorldParams>>& world_param_rows();

struct World {
  Mesh mesh;
  std::map<std::string, int> counts;  ///< objects by kind, triangles
};

/// The world along `path` (T_world_sensor, z up). Throws std::invalid_argument for an empty path
/// or a ground grid beyond 4096 cells a side.
World build_street_world(const std::vector<Rigid<3>>& path, const WorldParams& params);

/// A drawn drive around a `width` x `height` rectangular block, `laps` times, counter-clockwise
/// from the origin along +x, one pose every `step` metres (heading along the side, z = 0): every
/// lap after the first revisits the first, a loop-closure test without a recorded trajectory.
/// Throws std::invalid_argument (naming the values) for a size or step <= 0 (or NaN), laps < 0, or
/// more than 1e7 poses.
std::vector<Rigid<3>> block_laps(double width, double height, int laps, double step = 1.0);

}  // namespace verifybench
