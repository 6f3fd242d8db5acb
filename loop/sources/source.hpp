#pragma once
// The loop's first stage: a recorded sequence, read in the layout its dataset publishes. A source
// lists its scans in time order, with each scan's timestamp, the poses the recording carries (a
// reference, or odometry; the loop's --reference and --odometry say which), and reads one scan's
// points in the sensor frame on demand. One file per layout (KISS-ICP's dataloaders do the same),
// each citing its dataset's documentation; the registry below picks one by name or by detection.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "datasets/trajectory.hpp"

namespace verifybench {

using Cloud = std::vector<Eigen::Vector3f>;

/// What a source knows of its sequence once opened (no scan's points built yet).
struct SequenceInfo {
  std::string format;  ///< the registry name ("kitti", "folder", ...)
  std::string dir;     ///< the folder (or log file) opened
  /// [s] per scan, ascending; the scan index where the layout has none.
  std::vector<double> stamps;
  /// T_world_sensor per scan, z up, from the recording's own pose file (ground truth for kitti,
  /// mulran, helipr, nclt; the corrected log for carmen when given); empty when there is none.
  /// Only differences matter: a layout may move the world's origin (mulran: to the first scan).
  Trajectory poses;
  std::string poses_file;  ///< where `poses` came from ("" when empty)
  /// The recording's own odometry per scan (carmen's wheel odometry); empty otherwise.
  Trajectory odometry;
  /// The recording's whole odometry stream, every scan's (kept or not), ascending stamps: what
  /// carries an estimate between frames (loop/relations.hpp); empty without logged odometry.
  std::vector<double> odometry_stream_stamps;
  Trajectory odometry_stream;
  bool planar = false;  ///< 2D laser scans: points in the sensor's x-y plane, z = 0
  /// Scans the recording holds; more than size() when some were left out (no pose to match).
  int recorded = 0;
  /// How scans, stamps and poses were matched and what was left out, one line ("" when nothing).
  std::string note;
};

class SequenceSource {
 public:
  virtual ~SequenceSource() = default;
  virtual const SequenceInfo& info() const = 0;
  int size() const { return static_cast<int>(info().stamps.size()); }
  /// Scan i's points in the sensor frame, (0, 0, 0) returns and out-of-range laser readings
  /// dropped. Throws InputError naming the file, the byte offset or line, the field and the value
  /// (a size that is not whole records, a non-finite coordinate); std::out_of_range for a bad i.
  virtual Cloud points(int i) const = 0;
};

/// Options a layout may need; each reader says which it reads.
struct SourceOptions {
  /// folder: a TUM or KITTI poses file (else DIR/poses.txt, poses.tum or groundtruth.txt)
  std::string poses_file;
  std::string sensor;  ///< helipr: Ouster, Velodyne, Aeva or Avia ("" = the one present)
  /// carmen: a corrected log whose FLASER poses are the reference; only the scans it corrects are
  /// kept (corrected logs are subsampled).
  std::string reference;
};

struct SourceInfo {
  std::string name;
  std::string help;  ///< one line for --help and README
  /// True when `dir` is unambiguously in this layout.
  std::function<bool(const std::string& dir)> detect;
  std::function<std::unique_ptr<SequenceSource>(const std::string& dir, const SourceOptions&)> open;
};

/// Adds a layout to the built-in ones (std::logic_error on a duplicate name).
void register_source(SourceInfo info);
std::vector<SourceInfo> list_sources();  ///< by name

/// Opens `dir` as `format`, or by detection when `format` is empty. std::invalid_argument listing
/// the formats for an unknown name or when no layout or several match; InputError for a missing
/// or malformed file.
std::unique_ptr<SequenceSource> open_sequence(const std::string& dir, const std::string& format,
                                              const SourceOptions& options = {});

}  // namespace verifybench
