#include "datasets/dump_clouds.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"

namespace verifybench {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr std::uintmax_t kRecordBytes = 16;  // float32 x, y, z, reflectance

void write_cloud(const fs::path& file, const std::vector<Eigen::Vector3f>& points,
                 const char* side) {
  if (points.empty()) throw std::invalid_argument(std::string("kept clouds: the ") + side +
                                                  " cloud is empty");
  std::ofstream out(file, std::ios::binary);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f& p = points[i];
    if (!p.allFinite()) {
      throw std::invalid_argument(std::string("kept clouds: ") + side + " point " +
                                  std::to_string(i) + " is not finite");
    }
    const float record[4] = {p.x(), p.y(), p.z(), 0.0f};
    out.write(reinterpret_cast<const char*>(record), sizeof record);
  }
  out.flush();
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::vector<Eigen::Vector3f> read_cloud_file(const fs::path& dir, const json& entry,
                                             const char* side, std::size_t index) {
  const fs::path meta = dir / "dump.json";
  if (!entry.contains(side) || !entry[side].is_string()) {
    input_error(meta.string(), 0, std::string("field clouds.") + side + " is not a file name");
  }
  const std::string name = entry[side].get<std::string>();
  const fs::path rel(name);
  if (name.empty() || rel.is_absolute() || rel.has_parent_path() || name == "." || name == "..") {
    input_error(meta.string(), 0, std::string("field clouds.") + side + " = \"" + name +
                                      "\": a file name inside the dump folder is expected");
  }
  const json& counts = entry.contains("points") ? entry["points"] : json();
  if (!counts.is_array() || counts.size() != 2 || !counts[index].is_number_integer()) {
    input_error(meta.string(), 0, "field clouds.points is not [n_source, n_target]");
  }
  const long long declared = counts[index].get<long long>();
  if (declared <= 0 || declared > kMaxDumpCloudPoints) {
    input_error(meta.string(), 0, std::string("field clouds.points[") + std::to_string(index) +
                                      "] = " + std::to_string(declared) + "; expected 1 to " +
                                      std::to_string(kMaxDumpCloudPoints));
  }
  const fs::path file = dir / rel;
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(file, ec);
  if (ec) input_error(file.string(), 0, "cannot read the kept " + std::string(side) +
                                            " cloud: " + ec.message());
  if (bytes != static_cast<std::uintmax_t>(declared) * kRecordBytes) {
    input_error(file.string(), 0,
                "is " + std::to_string(bytes) + " bytes; dump.json declares " +
                    std::to_string(declared) + " points of 16 bytes (float32 x y z r)");
  }
  std::ifstream in(file, std::ios::binary);
  std::vector<Eigen::Vector3f> points(static_cast<std::size_t>(declared));
  for (std::size_t i = 0; i < points.size(); ++i) {
    float record[4];
    if (!in.read(reinterpret_cast<char*>(record), sizeof record)) {
      input_error(file.string(), 0, "cannot read point " + std::to_string(i));
    }
    for (int d = 0; d < 3; ++d) {
      if (!std::isfinite(record[d])) {
        input_error(file.string(), 0, "point " + std::to_string(i) + " field " +
                                          "xyz"[d] + " = " + std::to_string(record[d]) +
                                          " is not finite");
      }
    }
    points[i] = Eigen::Vector3f(record[0], record[1], record[2]);
  }
  return points;
}

}  // namespace

json write_dump_clouds(const fs::path& dir, const DumpClouds& clouds) {
  write_cloud(dir / "source_cloud.bin", clouds.source, "source");
  write_cloud(dir / "target_cloud.bin", clouds.target, "target");
  return {{"source", "source_cloud.bin"},
          {"target", "target_cloud.bin"},
          {"points", {clouds.source.size(), clouds.target.size()}},
          {"voxel_m", clouds.voxel}};
}

DumpClouds read_dump_clouds(const fs::path& dir, const json& entry) {
  if (!entry.is_object()) {
    input_error((dir / "dump.json").string(), 0, "field clouds is not an object");
  }
  DumpClouds c;
  c.source = read_cloud_file(dir, entry, "source", 0);
  c.target = read_cloud_file(dir, entry, "target", 1);
  if (entry.contains("voxel_m")) {
    if (!entry["voxel_m"].is_number() || !(entry["voxel_m"].get<double>() >= 0.0)) {
      input_error((dir / "dump.json").string(), 0,
                  "field clouds.voxel_m = " + entry["voxel_m"].dump() + " is not a size >= 0");
    }
    c.voxel = entry["voxel_m"].get<double>();
  }
  return c;
}

}  // namespace verifybench
