#include "frontend/cloud_io.hpp"

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "frontend/cloud_header.hpp"
#include "core/transform.hpp"

namespace verifybench {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  input_error(path, 0, what);
}

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

Cloud read_kitti_bin(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  in.seekg(0, std::ios::end);
  const auto bytes = static_cast<std::size_t>(in.tellg());
  in.seekg(0);
  if (bytes % 16 != 0) {
    fail(path, std::to_string(bytes) + " bytes is not a whole number of 16-byte KITTI records");
  }
  std::vector<float> raw(bytes / 4);
  in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(bytes));
  if (!in) fail(path, "read failed");
  Cloud cloud(bytes / 16);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    cloud[i] = {raw[4 * i], raw[4 * i + 1], raw[4 * i + 2]};
  return cloud;
}

Cloud read_with_pcl(const std::string& path, const std::string& ext) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  if (ext == ".pcd") {
    check_pcd_header(path);
  } else {
    check_ply_header(path);
  }
  pcl::PointCloud<pcl::PointXYZ> pc;
  const int rc = ext == ".pcd" ? pcl::io::loadPCDFile(path, pc) : pcl::io::loadPLYFile(path, pc);
  if (rc < 0) fail(path, "PCL's " + ext.substr(1) + " reader could not parse it");
  Cloud cloud;
  cloud.reserve(pc.size());
  for (const auto& p : pc) cloud.emplace_back(p.x, p.y, p.z);
  return cloud;
}

}  // namespace

Cloud read_cloud(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) fail(path, "no such file");
  const std::string ext = extension(path);
  Cloud cloud;
  if (ext == ".bin") {
    cloud = read_kitti_bin(path);
  } else if (ext == ".pcd" || ext == ".ply") {
    cloud = read_with_pcl(path, ext);
  } else {
    fail(path, "unknown point cloud extension '" + ext + "' (expected .bin, .pcd or .ply)");
  }
  if (cloud.empty()) fail(path, "the cloud has no points");
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud[i].allFinite()) {
      std::ostringstream msg;
      msg << "point " << i << " is not finite (" << cloud[i].transpose() << ")";
      fail(path, msg.str());
    }
  }
  return cloud;
}

Rigid<3> read_transform(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open");
  std::vector<double> v;
  std::string token;
  while (in >> token) {
    const ParsedReal x = parse_real_token(token);
    if (x.error != NumberError::none) {
      fail(path,
           "value " + std::to_string(v.size() + 1) + " '" + token + "' is not a finite number");
    }
    v.push_back(x.value);
  }
  if (v.size() != 12 && v.size() != 16) {
    fail(path, std::to_string(v.size()) + " numbers; expected 12 (3x4) or 16 (4x4), row-major");
  }
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  for (std::size_t k = 0; k < v.size(); ++k)
    M(static_cast<int>(k / 4), static_cast<int>(k % 4)) = v[k];
  return published_rigid<3>(M, path).T;
}

}  // namespace verifybench
