#include "loop/sources/common.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"

namespace verifybench::sources {
namespace fs = std::filesystem;

Cloud read_records(const std::string& path, const PointRecord& record) {
  std::ifstream in(path, std::ios::binary);
  if (!in) input_error(path, 0, "cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() % static_cast<std::size_t>(record.bytes) != 0) {
    input_error(path, 0,
                std::to_string(bytes.size()) + " bytes is not a whole number of " +
                    std::to_string(record.bytes) + "-byte records (" + record.what + ")");
  }
  const std::size_t n = bytes.size() / static_cast<std::size_t>(record.bytes);
  const int offsets[3] = {record.x, record.y, record.z};
  Cloud cloud;
  cloud.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const char* r = bytes.data() + i * static_cast<std::size_t>(record.bytes);
    Eigen::Vector3f p;
    for (int k = 0; k < 3; ++k) {
      double v;
      if (record.uint16) {
        std::uint16_t u;
        std::memcpy(&u, r + offsets[k], sizeof u);
        v = u;
      } else {
        float f;
        std::memcpy(&f, r + offsets[k], sizeof f);
        v = f;
      }
      if (!std::isfinite(v)) {
        std::ostringstream msg;
        msg << "byte " << i * static_cast<std::size_t>(record.bytes) + offsets[k] << " (point " << i
            << ", field "
            << "xyz"[k] << "): " << v << " is not a finite coordinate (" << record.what << ")";
        input_error(path, 0, msg.str());
      }
      p[k] = static_cast<float>(v * record.scale + record.offset);
    }
    if (!(p.x() == 0 && p.y() == 0 && p.z() == 0)) cloud.push_back(p);
  }
  return cloud;
}

std::vector<std::string> list_scans(const std::string& dir,
                                    const std::vector<std::string>& extensions) {
  struct Entry {
    std::string path, name;
    double stem = 0;
    bool numeric = false;
  };
  std::vector<Entry> entries;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec)) continue;
    std::string ext = e.path().extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) continue;
    const ParsedReal stem = parse_real_token(e.path().stem().string());
    entries.push_back({e.path().string(), e.path().filename().string(), stem.value,
                       stem.error == NumberError::none});
  }
  if (ec) input_error(dir, 0, "cannot list the folder: " + ec.message());
  const bool numeric =
      std::all_of(entries.begin(), entries.end(), [](const Entry& e) { return e.numeric; });
  std::sort(entries.begin(), entries.end(), [numeric](const Entry& a, const Entry& b) {
    if (numeric && a.stem != b.stem) return a.stem < b.stem;
    return a.name < b.name;
  });
  std::vector<std::string> files;
  for (auto& e : entries) files.push_back(std::move(e.path));
  return files;
}

std::uint64_t stem_integer(const std::string& path) {
  const std::string stem = fs::path(path).stem().string();
  const auto v = parse_unsigned_token(stem);
  if (!v) input_error(path, 0, "file name '" + stem + "' is not a stamp (an unsigned integer)");
  return *v;
}

int nearest_stamp(const std::vector<double>& ref, double t, double tolerance) {
  if (ref.empty()) return -1;
  const auto it = std::lower_bound(ref.begin(), ref.end(), t);
  std::size_t best = it == ref.end() ? ref.size() - 1 : static_cast<std::size_t>(it - ref.begin());
  if (best > 0 && std::abs(ref[best - 1] - t) <= std::abs(ref[best] - t)) --best;
  return std::abs(ref[best] - t) <= tolerance ? static_cast<int>(best) : -1;
}

void keep_scans_with_pose(SequenceInfo& info, std::vector<std::string>& files,
                          const std::vector<int>& pose_index, const Trajectory& poses,
                          const std::string& why) {
  std::vector<std::string> kept_files;
  std::vector<double> kept_stamps;
  info.poses.clear();
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (pose_index[i] < 0) continue;
    kept_files.push_back(files[i]);
    kept_stamps.push_back(info.stamps[i]);
    info.poses.push_back(poses[static_cast<std::size_t>(pose_index[i])]);
  }
  const std::size_t dropped = files.size() - kept_files.size();
  if (dropped > 0) {
    info.note = "kept " + std::to_string(kept_files.size()) + " of " +
                std::to_string(files.size()) + " scans: " + std::to_string(dropped) + " " + why;
  }
  files = std::move(kept_files);
  info.stamps = std::move(kept_stamps);
  if (files.empty()) input_error(info.poses_file, 0, "no scan has a pose (" + why + ")");
}

bool is_dir(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

bool is_file(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

void require_dir(const std::string& path, const std::string& what) {
  if (!is_dir(path)) input_error(path, 0, "no such folder (" + what + ")");
}

void require_file(const std::string& path, const std::string& what) {
  if (!is_file(path)) input_error(path, 0, "no such file (" + what + ")");
}

Rigid<3> pose_xyz_rpy(double x, double y, double z, double roll, double pitch, double yaw) {
  Rigid<3> T = Rigid<3>::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() << x, y, z;
  return T;
}

Cloud FileSequence::points(int i) const {
  if (i < 0 || i >= size()) {
    throw std::out_of_range("scan " + std::to_string(i) + " of " + std::to_string(size()) + " in " +
                            info_.dir);
  }
  return read_(files_[static_cast<std::size_t>(i)]);
}

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  for (std::istringstream row(line); std::getline(row, field, ',');) {
    const auto a = field.find_first_not_of(" \t\r"), b = field.find_last_not_of(" \t\r");
    fields.push_back(a == std::string::npos ? "" : field.substr(a, b - a + 1));
  }
  return fields;
}

SequenceInfo stamped_scans(const std::string& dir, const std::string& sub, const std::string& what,
                           const std::string& format, double unit, std::vector<std::string>& files) {
  const std::string folder = (std::filesystem::path(dir) / sub).string();
  require_dir(folder, what);
  files = list_scans(folder, {".bin"});
  if (files.empty()) input_error(folder, 0, "no .bin scan");
  SequenceInfo info;
  info.format = format;
  info.dir = dir;
  info.recorded = static_cast<int>(files.size());
  for (const auto& f : files) info.stamps.push_back(static_cast<double>(stem_integer(f)) * unit);
  return info;
}

}  // namespace verifybench::sources
