#pragma once
// What the layouts share (internal to loop/sources): fixed-size binary point records, a folder's
// scan files in time order, stamps in file names, nearest-stamp matching, and a source that reads
// one file per scan. Each layout's file only describes its layout with these.
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "loop/sources/source.hpp"

namespace verifybench::sources {

/// One binary point record. Every layout here is written little-endian, as x86 hosts store it.
struct PointRecord {
  std::string what;         ///< for messages: "KITTI: float32 x y z reflectance"
  int bytes = 16;           ///< record size
  int x = 0, y = 4, z = 8;  ///< byte offsets of the coordinates within a record
  bool uint16 = false;      ///< coordinates stored as uint16 (NCLT) rather than float32
  double scale = 1.0;       ///< coordinate = stored value * scale + offset
  double offset = 0.0;
};

/// Every record of `path` as a point, (0, 0, 0) returns dropped. Throws InputError naming the
/// file and its byte count when that is not whole records, or the byte offset, point and field of
/// a non-finite coordinate.
Cloud read_records(const std::string& path, const PointRecord& record);

/// The regular files in `dir` with one of `extensions` (lower case, with the dot), in time
/// order: by the numeric value of their stems when every stem is a number, else by name.
std::vector<std::string> list_scans(const std::string& dir,
                                    const std::vector<std::string>& extensions);

/// The file's stem as an unsigned integer (a stamp in the layout's unit); InputError otherwise.
std::uint64_t stem_integer(const std::string& path);

/// The index of the stamp in `ref` (ascending) nearest to t, or -1 when it is farther than
/// `tolerance` [s] (or ref is empty).
int nearest_stamp(const std::vector<double>& ref, double t, double tolerance);

/// Keeps the scans whose pose_index is not -1, giving each its pose from `poses`; notes how many
/// were left out and why. `files` and info.stamps shrink in step.
void keep_scans_with_pose(SequenceInfo& info, std::vector<std::string>& files,
                          const std::vector<int>& pose_index, const Trajectory& poses,
                          const std::string& why);

/// The .bin scans of DIR/SUB in stamp order (stems are integer stamps in units of `unit` seconds):
/// their files, and a SequenceInfo of `format` with dir, recorded and stamps filled in. InputError
/// when the folder ("what" says what it should hold) is missing or holds no scan.
SequenceInfo stamped_scans(const std::string& dir, const std::string& sub, const std::string& what,
                           const std::string& format, double unit, std::vector<std::string>& files);

/// The comma-separated fields of a CSV line, each trimmed of blanks (MulRan's and NCLT's poses).
std::vector<std::string> csv_fields(const std::string& line);

/// InputError "PATH: no such folder (WHAT)" / "... file" unless it exists.
void require_dir(const std::string& path, const std::string& what);
void require_file(const std::string& path, const std::string& what);
bool is_dir(const std::string& path);   ///< never throws
bool is_file(const std::string& path);  ///< never throws

/// T = Rz(yaw) Ry(pitch) Rx(roll) with translation t, angles in radians.
Rigid<3> pose_xyz_rpy(double x, double y, double z, double roll, double pitch, double yaw);

/// One file per scan, read by `read` (a layout's record reader).
class FileSequence : public SequenceSource {
 public:
  using Reader = std::function<Cloud(const std::string& file)>;
  FileSequence(SequenceInfo info, std::vector<std::string> files, Reader read)
      : info_(std::move(info)), files_(std::move(files)), read_(std::move(read)) {}
  const SequenceInfo& info() const override { return info_; }
  Cloud points(int i) const override;

 private:
  SequenceInfo info_;
  std::vector<std::string> files_;  // one per scan, in step with info_.stamps
  Reader read_;
};

// The built-in layouts, one file each.
SourceInfo carmen_source();
SourceInfo folder_source();
SourceInfo helipr_source();
SourceInfo kitti_source();
SourceInfo mulran_source();
SourceInfo nclt_source();

}  // namespace verifybench::sources
