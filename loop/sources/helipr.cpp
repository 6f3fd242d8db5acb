// HeLiPR (Jung et al., IJRR 2024; https://sites.google.com/view/heliprdataset). Point records as
// the authors' HeLiPR-Pointcloud-Toolbox reads them (src/PointCloudProcessor.cpp readBinFile,
// include/utility.h) and KISS-ICP's python/kiss_icp/datasets/helipr.py unpacks them (packed,
// little-endian):
//   DIR/LiDAR/<Sensor>/<ns stamp>.bin
//     Ouster    26 B: float32 x y z intensity, uint32 t, uint16 reflectivity ring ambient
//     Velodyne  22 B: float32 x y z intensity, uint16 ring, float32 time
//     Aeva      29 B: float32 x y z reflectivity velocity, int32 time_offset_ns, uint8 line_index,
//               float32 intensity; 25 B (no intensity) up to stamp 1691936557946849179
//     Avia      19 B: float32 x y z, uint8 reflectivity tag line, uint32 offset_time
//   DIR/LiDAR_GT/<Sensor>_gt.txt  `ns_stamp x y z qx qy qz qw` a line: the sensor's pose in a
//                                 local east-north-up frame (the toolbox's transformINStoLiDAR.py)
// Scans take the pose nearest their stamp within kTolerance; KISS-ICP keeps only the scans with a
// pose, and so do we (the note says how many were left out).
#include <filesystem>

#include "core/errors.hpp"
#include "loop/sources/common.hpp"

namespace verifybench::sources {
namespace {
namespace fs = std::filesystem;

constexpr double kTolerance = 0.05;  // [s] half a 10 Hz period
constexpr std::uint64_t kAevaIntensityAfter = 1691936557946849179ULL;
const char* const kSensors[] = {"Aeva", "Avia", "Ouster", "Velodyne"};

PointRecord record_of(const std::string& sensor, std::uint64_t stamp) {
  if (sensor == "Ouster") return {"HeLiPR Ouster: 26-byte records", 26};
  if (sensor == "Velodyne") return {"HeLiPR Velodyne: 22-byte records", 22};
  if (sensor == "Avia") return {"HeLiPR Avia: 19-byte records", 19};
  if (stamp <= kAevaIntensityAfter)
    return {"HeLiPR Aeva, early (no intensity): 25-byte records", 25};
  return {"HeLiPR Aeva: 29-byte records", 29};
}

std::string known_sensors() {
  std::string s;
  for (const char* name : kSensors) s += (s.empty() ? "" : ", ") + std::string(name);
  return s;
}

// The sensor asked for, or the only one recorded.
std::string choose_sensor(const fs::path& lidar, const std::string& asked) {
  if (!asked.empty()) {
    bool known = false;
    for (const char* name : kSensors) known = known || asked == name;
    if (!known) {
      throw std::invalid_argument("HeLiPR sensor '" + asked +
                                  "' is unknown (known: " + known_sensors() + ")");
    }
    require_dir((lidar / asked).string(), "HeLiPR scans of the sensor asked for");
    return asked;
  }
  std::vector<std::string> present;
  for (const char* name : kSensors) {
    if (is_dir((lidar / name).string())) present.push_back(name);
  }
  if (present.size() != 1) {
    std::string list;
    for (const auto& p : present) list += (list.empty() ? "" : ", ") + p;
    input_error(lidar.string(), 0,
                present.empty()
                    ? "no sensor folder (" + known_sensors() + ")"
                    : "several sensors (" + list + "): choose one (SourceOptions::sensor)");
  }
  return present[0];
}

std::unique_ptr<SequenceSource> open(const std::string& dir, const SourceOptions& options) {
  const fs::path lidar = fs::path(dir) / "LiDAR";
  require_dir(lidar.string(), "HeLiPR scans: DIR/LiDAR/<Sensor>/<ns stamp>.bin");
  const std::string sensor = choose_sensor(lidar, options.sensor);
  auto files = list_scans((lidar / sensor).string(), {".bin"});
  if (files.empty()) input_error((lidar / sensor).string(), 0, "no .bin scan");
  SequenceInfo info;
  info.format = "helipr";
  info.dir = dir;
  info.recorded = static_cast<int>(files.size());
  for (const auto& f : files) info.stamps.push_back(static_cast<double>(stem_integer(f)) * 1e-9);

  const std::string gt = (fs::path(dir) / "LiDAR_GT" / (sensor + "_gt.txt")).string();
  if (is_file(gt)) {
    info.poses_file = gt;
    StampedTrajectory poses = read_tum_poses(gt);
    for (double& t : poses.stamps) t *= 1e-9;  // ns
    std::vector<int> index;
    for (double t : info.stamps) index.push_back(nearest_stamp(poses.stamps, t, kTolerance));
    keep_scans_with_pose(info, files, index, poses.poses, "had no pose within 0.05 s");
  }
  return std::make_unique<FileSequence>(
      std::move(info), std::move(files), [sensor](const std::string& file) {
        return read_records(file, record_of(sensor, stem_integer(file)));
      });
}

}  // namespace

SourceInfo helipr_source() {
  return {"helipr",
          "HeLiPR: DIR/LiDAR/<Ouster|Velodyne|Aeva|Avia>/<ns>.bin, DIR/LiDAR_GT/<Sensor>_gt.txt "
          "(the sensor option picks one)",
          [](const std::string& dir) {
            for (const char* name : kSensors) {
              if (is_dir((fs::path(dir) / "LiDAR" / name).string())) return true;
            }
            return false;
          },
          open};
}

}  // namespace verifybench::sources
