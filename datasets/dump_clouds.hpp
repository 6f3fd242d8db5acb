#pragma once
// The two clouds a dump may keep beside its correspondences (`extract --keep-clouds`), for the
// dense check of an accepted motion (acceptance/dense_check.hpp). Each in its own sensor frame
// (the frames of the correspondences' source and target points), in the KITTI .bin layout
// (float32 x, y, z, reflectance; the reflectance written as 0 and ignored), so any KITTI reader
// opens them. dump.json names them:
//   "clouds": {"source": "source_cloud.bin", "target": "target_cloud.bin",
//              "points": [n_source, n_target], "voxel_m": V}
#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

namespace verifybench {

struct DumpClouds {
  std::vector<Eigen::Vector3f> source, target;
  double voxel = 0.0;  ///< [m] the grid they were thinned on (0 = as read)
};

/// At most this many points per kept cloud (16 bytes each): a declared count beyond it is refused
/// before anything is read.
constexpr long long kMaxDumpCloudPoints = 100'000'000;

/// Writes both files into `dir` and returns dump.json's "clouds" entry. Throws std::runtime_error
/// on an I/O failure, std::invalid_argument on an empty cloud or a non-finite point.
nlohmann::json write_dump_clouds(const std::filesystem::path& dir, const DumpClouds& clouds);

/// Reads the clouds that `entry` (dump.json's "clouds") names, relative to `dir`. Throws
/// InputError naming the file and what is wrong: a missing file, a name that leaves the folder, a
/// size that is not whole 16-byte records or disagrees with "points", a non-finite coordinate
/// (with its point index), an empty cloud.
DumpClouds read_dump_clouds(const std::filesystem::path& dir, const nlohmann::json& entry);

}  // namespace verifybench
