// Sequence sources (loop/sources/): each layout read from a fixture the test writes in that exact
// layout (binary records byte by byte, little-endian, pose files with poses the test chose), its
// scans, stamps, points and poses checked against those values after the layout's scaling and
// frame conventions; detection; bad input named by file, line or byte; TUM written and read back.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "datasets/trajectory.hpp"
#include "loop/relations.hpp"
#include "loop/sources/source.hpp"
#include "test_util.hpp"

namespace vb = verifybench;
namespace fs = std::filesystem;

namespace {

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() /
            ("vb_sources_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path operator/(const std::string& p) const { return path_ / p; }
  std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

// Little-endian bytes, written one at a time.
struct Bytes {
  std::string data;
  Bytes& u8(unsigned v) {
    data.push_back(static_cast<char>(v & 0xffu));
    return *this;
  }
  Bytes& u16(unsigned v) { return u8(v).u8(v >> 8); }
  Bytes& u32(std::uint32_t v) { return u16(v & 0xffffu).u16(v >> 16); }
  Bytes& f32(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u32(u);
  }
  void write(const fs::path& p) const {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << data;
  }
};

void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// Runs f, expecting an exception of type E whose message holds every one of `parts`.
template <class E = vb::InputError>
void expect_error(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one naming " << ::testing::PrintToString(parts);
  } catch (const E& e) {
    for (const auto& p : parts)
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
          << "'" << p << "' missing from: " << e.what();
  }
}

void expect_pose_near(const vb::Rigid<3>& a, const vb::Rigid<3>& b, double tol = 1e-6) {
  EXPECT_TRUE(a.matrix().isApprox(b.matrix(), tol) ||
              (a.matrix() - b.matrix()).cwiseAbs().maxCoeff() < tol)
      << "\n"
      << a.matrix() << "\n vs \n"
      << b.matrix();
}

std::string row_major(const vb::Rigid<3>& T) {
  std::ostringstream s;
  s.precision(17);
  for (int k = 0; k < 12; ++k) s << (k ? " " : "") << T.matrix()(k / 4, k % 4);
  return s.str();
}

vb::Rigid<3> pose_rpy(double x, double y, double z, double roll, double pitch, double yaw) {
  vb::Rigid<3> T = vb::Rigid<3>::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() << x, y, z;
  return T;
}

// Each layout's detect() holds for `dir` exactly when it is `expected`; open_sequence agrees.
void expect_detected_as(const std::string& dir, const std::string& expected) {
  for (const auto& s : vb::list_sources()) {
    EXPECT_EQ(s.detect(dir), s.name == expected) << s.name << " on " << dir;
  }
  EXPECT_EQ(vb::open_sequence(dir, "")->info().format, expected);
}

// KITTI-style 16-byte records: x y z reflectance.
Bytes kitti_points(const std::vector<Eigen::Vector3f>& points) {
  Bytes b;
  for (const auto& p : points) b.f32(p.x()).f32(p.y()).f32(p.z()).f32(0.5f);
  return b;
}

// Exact values (to the float) by default; within `tol` for computed ones (ranges and bearings).
void expect_points(const vb::Cloud& got, const std::vector<Eigen::Vector3f>& want, float tol = 0) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (tol == 0) {
        EXPECT_FLOAT_EQ(got[i][k], want[i][k]) << "point " << i << " coordinate " << k;
      } else {
        EXPECT_NEAR(got[i][k], want[i][k], tol) << "point " << i << " coordinate " << k;
      }
    }
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// TUM files

TEST(TumPoses, WriteThenReadGivesTheDrawnPoses) {
  std::mt19937_64 rng(7);
  vb::Trajectory poses;
  std::vector<double> stamps;
  for (int i = 0; i < 50; ++i) {
    poses.push_back(vb::test::random_rigid<3>(rng, 100.0));
    stamps.push_back(1700000000.0 + 0.1 * i + 1e-7 * i);
  }
  TempDir tmp;
  const std::string path = (tmp / "traj.tum").string();
  vb::write_tum_poses(path, stamps, poses);
  const vb::StampedTrajectory back = vb::read_tum_poses(path);
  ASSERT_EQ(back.poses.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(back.stamps[i], stamps[i], 1e-6);
    EXPECT_LT((back.poses[i].translation() - poses[i].translation()).norm(), 1e-6);
    EXPECT_LT((back.poses[i].linear() - poses[i].linear()).norm(), 1e-8);
  }
  const vb::StampedTrajectory detected = vb::read_poses_file(path);
  EXPECT_EQ(detected.stamps.size(), poses.size());
}

TEST(TumPoses, EachLineIsEightSpaceSeparatedNumbersWithAUnitQuaternion) {
  vb::Trajectory poses{vb::Rigid<3>::Identity(), pose_rpy(1, 2.5, -3, 0, 0, M_PI / 2)};
  std::mt19937_64 rng(3);
  for (int i = 0; i < 10; ++i) poses.push_back(vb::test::random_rigid<3>(rng));
  std::vector<double> stamps;
  for (std::size_t i = 0; i < poses.size(); ++i) stamps.push_back(1.5 + static_cast<double>(i));
  TempDir tmp;
  const std::string path = (tmp / "traj.txt").string();
  vb::write_tum_poses(path, stamps, poses);

  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), poses.size());
  EXPECT_EQ(lines[0], "1.500000000 0 0 0 0 0 0 1");
  EXPECT_EQ(lines[1], "2.500000000 1 2.5 -3 0 0 0.707106781 0.707106781");
  for (const auto& line : lines) {
    std::vector<double> v;
    std::size_t start = 0;
    while (true) {  // single spaces, no leading or trailing blank
      const std::size_t end = line.find(' ', start);
      const std::string token = line.substr(start, end - start);
      ASSERT_FALSE(token.empty()) << line;
      char* stop = nullptr;
      v.push_back(std::strtod(token.c_str(), &stop));
      EXPECT_EQ(*stop, '\0') << token;
      EXPECT_TRUE(std::isfinite(v.back()));
      if (end == std::string::npos) break;
      start = end + 1;
    }
    ASSERT_EQ(v.size(), 8u) << line;
    EXPECT_EQ(line.substr(0, line.find(' ')).size() - line.find('.'), 10u) << "%.9f stamp";
    EXPECT_NEAR(std::hypot(std::hypot(v[4], v[5]), std::hypot(v[6], v[7])), 1.0, 1e-8);
    EXPECT_GE(v[7], 0.0);
  }
}

TEST(TumPoses, BadLinesAreNamedByFileLineAndField) {
  TempDir tmp;
  const std::string path = (tmp / "bad.tum").string();
  auto read = [&] { vb::read_tum_poses(path); };
  write_text(path, "# stamp x y z qx qy qz qw\n0 0 0 0 0 0 0 1\n1 0 0 0 0 0 1\n");
  expect_error(read, {path + ":3", "7 fields", "8"});
  write_text(path, "0 0 0 0 0 0 0 1\n1 0 0 0 abc 0 0 1\n");
  expect_error(read, {path + ":2", "field 5 (qx)", "'abc'"});
  write_text(path, "0 0 0 0 0 0 0 1\n1 0 0 nan 0 0 0 1\n");
  expect_error(read, {path + ":2", "field 4 (tz)", "'nan'"});
  write_text(path, "0 0 0 0 0 0 0 0.5\n");
  expect_error(read, {path + ":1", "norm 0.5"});
  write_text(path, "1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
  expect_error(read, {path + ":2", "timestamp", "not after"});
  write_text(path, "0 0 0 0 0 0 0 1.0005\n");  // within 1e-3: normalised
  EXPECT_NEAR(vb::read_tum_poses(path).poses[0].linear().determinant(), 1.0, 1e-12);
}

TEST(PosesFile, TellsTumFromKittiByTheFieldCount) {
  TempDir tmp;
  const std::string kitti = (tmp / "k.txt").string();
  write_text(kitti, "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 2 0 1 0 0 0 0 1 0\n");
  const auto k = vb::read_poses_file(kitti);
  EXPECT_TRUE(k.stamps.empty());
  ASSERT_EQ(k.poses.size(), 2u);
  EXPECT_DOUBLE_EQ(k.poses[1].translation().x(), 2.0);
  write_text(kitti, "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 2 0 1 0 0 0 0 1\n");
  expect_error([&] { vb::read_poses_file(kitti); }, {kitti + ":2", "11 numbers"});
  write_text(kitti, "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 2 0 1 0 x 0 0 1 0\n");
  expect_error([&] { vb::read_poses_file(kitti); }, {kitti + ":2", "field 8 'x'"});
  write_text(kitti, "1 2 3 4 5 6 7 8 9 10\n");
  expect_error([&] { vb::read_poses_file(kitti); }, {kitti + ":1", "10 fields", "TUM", "KITTI"});
}

// ---------------------------------------------------------------------------------------------
// kitti

namespace {

const std::vector<std::vector<Eigen::Vector3f>> kScans = {
    {{1.5f, -2.25f, 0.125f}, {10.0f, 20.0f, -1.0f}},
    {{0.0f, 0.0f, 0.0f}, {-3.0f, 4.0f, 5.0f}},  // the (0, 0, 0) return is dropped
    {{7.0f, 8.0f, 9.0f}}};

std::vector<Eigen::Vector3f> without_zeros(const std::vector<Eigen::Vector3f>& points) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : points) {
    if (!p.isZero(0.0f)) out.push_back(p);
  }
  return out;
}

// A KITTI sequence folder; returns the Velodyne poses its camera poses encode.
vb::Trajectory write_kitti(const fs::path& seq, const fs::path& poses_path) {
  for (std::size_t i = 0; i < kScans.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "%06zu.bin", i);
    kitti_points(kScans[i]).write(seq / "velodyne" / name);
  }
  const vb::Rigid<3> Tr = pose_rpy(0.27, -0.01, -0.08, -M_PI / 2, 0.01, -M_PI / 2);
  write_text(seq / "calib.txt", "P0: 1 0 0 0 0 1 0 0 0 0 1 0\nTr: " + row_major(Tr) + "\n");
  write_text(seq / "times.txt", "0.000000e+00\n1.036000e-01\n2.072000e-01\n");
  const vb::Trajectory velodyne{vb::Rigid<3>::Identity(), pose_rpy(1, 0.2, 0, 0, 0, 0.1),
                                pose_rpy(2, 0.5, 0.1, 0.01, 0, 0.3)};
  std::string text;
  for (const auto& V : velodyne) text += row_major(Tr * V * Tr.inverse()) + "\n";
  write_text(poses_path, text);
  return velodyne;
}

}  // namespace

TEST(KittiSource, ReadsScansStampsAndVelodynePoses) {
  TempDir tmp;
  const fs::path seq = tmp / "seq";
  const vb::Trajectory truth = write_kitti(seq, seq / "poses.txt");
  const auto src = vb::open_sequence(seq.string(), "kitti");
  const auto& info = src->info();
  ASSERT_EQ(src->size(), 3);
  EXPECT_EQ(info.stamps, (std::vector<double>{0.0, 0.1036, 0.2072}));
  EXPECT_EQ(info.poses_file, (seq / "poses.txt").string());
  ASSERT_EQ(info.poses.size(), 3u);
  for (int i = 0; i < 3; ++i) expect_pose_near(info.poses[i], truth[i], 1e-9);
  for (int i = 0; i < 3; ++i) expect_points(src->points(i), without_zeros(kScans[i]));
  EXPECT_FALSE(info.planar);
  EXPECT_TRUE(info.odometry.empty());
  expect_detected_as(seq.string(), "kitti");
}

TEST(KittiSource, FindsPosesInTheDownloadLayoutAndRunsWithoutThem) {
  TempDir tmp;
  const fs::path seq = tmp / "dataset" / "sequences" / "07";
  const vb::Trajectory truth = write_kitti(seq, tmp / "dataset" / "poses" / "07.txt");
  const auto src = vb::open_sequence(seq.string(), "");
  ASSERT_EQ(src->info().poses.size(), 3u);
  expect_pose_near(src->info().poses[2], truth[2], 1e-9);

  fs::remove(tmp / "dataset" / "poses" / "07.txt");
  fs::remove(seq / "times.txt");
  const auto bare = vb::open_sequence(seq.string(), "kitti");
  EXPECT_TRUE(bare->info().poses.empty());
  EXPECT_EQ(bare->info().stamps, (std::vector<double>{0, 1, 2}));
}

TEST(KittiSource, BadInputIsNamed) {
  TempDir tmp;
  const fs::path seq = tmp / "seq";
  write_kitti(seq, seq / "poses.txt");
  const std::string scan = (seq / "velodyne" / "000001.bin").string();
  Bytes truncated = kitti_points(kScans[1]);
  truncated.data.resize(20);
  truncated.write(scan);
  auto src = vb::open_sequence(seq.string(), "kitti");
  expect_error([&] { src->points(1); }, {scan, "20 bytes", "16-byte"});
  kitti_points({{1, 2, 3}, {4, std::nanf(""), 6}}).write(scan);
  expect_error([&] { src->points(1); }, {scan, "byte 20", "point 1", "field y", "nan"});
  EXPECT_THROW(src->points(3), std::out_of_range);

  std::ifstream in(seq / "poses.txt");
  std::string l1, l2;
  std::getline(in, l1);
  std::getline(in, l2);
  in.close();
  write_text(seq / "poses.txt", l1 + "\n" + l2 + "\n");
  expect_error([&] { vb::open_sequence(seq.string(), "kitti"); },
               {(seq / "poses.txt").string(), "2 poses for 3 scans"});
  write_text(seq / "poses.txt", l1 + "\n1 0 0 0 0 1 0 0 0 0 1\n" + l2 + "\n");
  expect_error([&] { vb::open_sequence(seq.string(), "kitti"); },
               {(seq / "poses.txt").string() + ":2", "11 numbers"});
  fs::remove(seq / "calib.txt");
  expect_error([&] { vb::open_sequence(seq.string(), "kitti"); }, {"calib.txt", "no such file"});
}

// ---------------------------------------------------------------------------------------------
// folder

TEST(FolderSource, MatchesPosesByTheStampsInTheFileNames) {
  TempDir tmp;
  const std::vector<std::string> stems = {"1700000000000000000", "1700000000100000000",
                                          "1700000000200000000"};  // [ns]
  for (std::size_t i = 0; i < stems.size(); ++i)
    kitti_points(kScans[i]).write(tmp / (stems[i] + ".bin"));
  // Poses every 0.05 s: scan i meets pose 2i (pose k sits at x = k).
  std::string tum = "# timestamp tx ty tz qx qy qz qw\n";
  for (int k = 0; k < 6; ++k) {
    char line[128];
    std::snprintf(line, sizeof line, "%.3f %d 0 0 0 0 0 1\n", 1700000000.0 + 0.05 * k, k);
    tum += line;
  }
  write_text(tmp / "poses.tum", tum);
  const auto src = vb::open_sequence(tmp.str(), "");
  const auto& info = src->info();
  EXPECT_EQ(info.format, "folder");
  ASSERT_EQ(src->size(), 3);
  ASSERT_EQ(info.poses.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(info.stamps[i], 1700000000.0 + 0.1 * i, 1e-6);
    EXPECT_NEAR(info.poses[i].translation().x(), 2.0 * i, 1e-12);
    expect_points(src->points(i), without_zeros(kScans[i]));
  }
  expect_detected_as(tmp.str(), "folder");

  // Poses 0.3 s apart around the middle scan: it has none within the tolerance.
  write_text(tmp / "poses.tum",
             "1700000000.0 0 0 0 0 0 0 1\n1700000000.05 0 0 0 0 0 0 1\n"
             "1700000000.35 0 0 0 0 0 0 1\n");
  expect_error([&] { vb::open_sequence(tmp.str(), "folder"); },
               {(tmp / (stems[1] + ".bin")).string(), "no pose"});
}

TEST(FolderSource, MatchesKittiPosesByIndexAndReadsPcd) {
  TempDir tmp;
  kitti_points(kScans[0]).write(tmp / "clouds" / "a.bin");
  write_text(tmp / "clouds" / "b.pcd",
             "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
             "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n1 2 3\n4.5 -5 6\n");
  const std::string poses = (tmp / "gt.txt").string();
  write_text(poses, "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 3 0 1 0 0 0 0 1 0\n");
  vb::SourceOptions options;
  options.poses_file = poses;
  const auto src = vb::open_sequence(tmp.str(), "folder", options);  // scans in the subfolder
  ASSERT_EQ(src->size(), 2);
  EXPECT_EQ(src->info().stamps, (std::vector<double>{0, 1}));
  EXPECT_EQ(src->info().poses_file, poses);
  EXPECT_DOUBLE_EQ(src->info().poses[1].translation().x(), 3.0);
  expect_points(src->points(0), kScans[0]);
  expect_points(src->points(1), {{1, 2, 3}, {4.5f, -5, 6}});

  write_text(poses, "1 0 0 0 0 1 0 0 0 0 1 0\n");
  expect_error([&] { vb::open_sequence(tmp.str(), "folder", options); },
               {poses, "1 poses for 2 scans"});
}

// ---------------------------------------------------------------------------------------------
// mulran

TEST(MulranSource, GivesOusterPosesFromBasePosesNearestInTime) {
  TempDir tmp;
  const std::uint64_t t0 = 1566535000000000000ULL;  // [ns]
  for (int i = 0; i < 4; ++i) {
    // The fourth scan comes 2 s after the last pose: left out.
    const std::uint64_t t = t0 + static_cast<std::uint64_t>(i < 3 ? i : 30) * 100000000ULL;
    kitti_points(kScans[static_cast<std::size_t>(i % 3)])
        .write(tmp / "Ouster" / (std::to_string(t) + ".bin"));
  }
  vb::Trajectory base;
  std::string csv;
  for (int k = 0; k < 12; ++k) {  // every 0.025 s, UTM-sized
    base.push_back(pose_rpy(353000.0 + k, 4026000.0 + 0.5 * k, 19.0, 0.001 * k, 0, 0.2 * k));
    csv += std::to_string(t0 + static_cast<std::uint64_t>(k) * 25000000ULL) + ",";
    std::string row = row_major(base.back());
    for (char& c : row) c = c == ' ' ? ',' : c;
    csv += row + "\n";
  }
  write_text(tmp / "global_pose.csv", csv);
  const auto src = vb::open_sequence(tmp.str(), "");
  const auto& info = src->info();
  EXPECT_EQ(info.format, "mulran");
  ASSERT_EQ(src->size(), 3);
  EXPECT_EQ(info.recorded, 4);
  EXPECT_NE(info.note.find("kept 3 of 4"), std::string::npos) << info.note;
  // calib_base2ouster as KISS-ICP's loader spells the matrix out.
  vb::Rigid<3> X = vb::Rigid<3>::Identity();
  X.matrix().topRows<3>() << -9.9998295e-01, -5.8398386e-03, -5.2257060e-06, 1.7042000e00,
      5.8398386e-03, -9.9998295e-01, 1.7758769e-06, -2.1000000e-02, -5.2359878e-06, 1.7453292e-06,
      1.0000000e00, 1.8047000e00;
  const Eigen::Vector3d origin = (base[0] * X).translation();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(info.stamps[i], 1566535000.0 + 0.1 * i, 1e-6);
    vb::Rigid<3> want = base[static_cast<std::size_t>(4 * i)] * X;
    want.translation() -= origin;
    expect_pose_near(info.poses[i], want, 1e-6);
    expect_points(src->points(i), without_zeros(kScans[i]));
  }
  expect_detected_as(tmp.str(), "mulran");

  write_text(tmp / "global_pose.csv", csv + "1566535000300000000,1,0,0,0,0,1,0,0,0,0,1\n");
  expect_error([&] { vb::open_sequence(tmp.str(), "mulran"); },
               {"global_pose.csv:13", "12 fields", "13"});
  write_text(tmp / "global_pose.csv", csv + "1566535000300000000,1,0,0,0,0,1,0,q,0,0,1,0\n");
  expect_error([&] { vb::open_sequence(tmp.str(), "mulran"); },
               {"global_pose.csv:13", "field 9 'q'"});
}

// ---------------------------------------------------------------------------------------------
// helipr

namespace {

// One scan's records in the sensor's layout, points p, the other fields filler.
Bytes helipr_points(const std::string& sensor, bool aeva_intensity,
                    const std::vector<Eigen::Vector3f>& points) {
  Bytes b;
  for (const auto& p : points) {
    b.f32(p.x()).f32(p.y()).f32(p.z());
    if (sensor == "Ouster") b.f32(12.0f).u32(123456u).u16(7).u16(31).u16(900);
    if (sensor == "Velodyne") b.f32(40.0f).u16(15).f32(0.05f);
    if (sensor == "Avia") b.u8(200).u8(0x10).u8(5).u32(99999u);
    if (sensor == "Aeva") {
      b.f32(0.7f).f32(-1.25f).u32(static_cast<std::uint32_t>(-4000)).u8(63);
      if (aeva_intensity) b.f32(0.9f);
    }
  }
  return b;
}

}  // namespace

TEST(HeliprSource, ReadsEachSensorsRecordLayout) {
  const std::vector<Eigen::Vector3f> points = {{1.25f, -2.5f, 3.75f}, {-10, 20, -0.5f}};
  for (const std::string sensor : {"Ouster", "Velodyne", "Avia", "Aeva"}) {
    SCOPED_TRACE(sensor);
    TempDir tmp;
    // Aeva: records gain an intensity after stamp 1691936557946849179.
    const std::vector<std::string> stamps = {"1691936557946849179", "1691936558046849179"};
    for (std::size_t i = 0; i < stamps.size(); ++i) {
      helipr_points(sensor, i == 1, points).write(tmp / "LiDAR" / sensor / (stamps[i] + ".bin"));
    }
    write_text(tmp / "LiDAR_GT" / (sensor + "_gt.txt"),
               "1691936557946849179 1 2 3 0 0 0 1\n1691936558046849179 4 5 6 0 0 1 0\n");
    const auto src = vb::open_sequence(tmp.str(), "");
    EXPECT_EQ(src->info().format, "helipr");
    ASSERT_EQ(src->size(), 2);
    EXPECT_NEAR(src->info().stamps[1] - src->info().stamps[0], 0.1, 1e-6);
    for (int i = 0; i < 2; ++i) expect_points(src->points(i), points);
    ASSERT_EQ(src->info().poses.size(), 2u);
    expect_pose_near(src->info().poses[1], pose_rpy(4, 5, 6, 0, 0, M_PI), 1e-12);
    expect_detected_as(tmp.str(), "helipr");
  }
}

TEST(HeliprSource, ChoosesTheSensorAndNamesBadRecords) {
  TempDir tmp;
  const std::vector<Eigen::Vector3f> points = {{1, 2, 3}};
  helipr_points("Ouster", false, points)
      .write(tmp / "LiDAR" / "Ouster" / "1692000000000000000.bin");
  helipr_points("Velodyne", false, points)
      .write(tmp / "LiDAR" / "Velodyne" / "1692000000000000000.bin");
  expect_error([&] { vb::open_sequence(tmp.str(), "helipr"); },
               {"several sensors", "Ouster, Velodyne"});
  vb::SourceOptions options;
  options.sensor = "Livox";
  expect_error<std::invalid_argument>([&] { vb::open_sequence(tmp.str(), "helipr", options); },
                                      {"'Livox'", "Aeva, Avia, Ouster, Velodyne"});
  options.sensor = "Velodyne";
  auto src = vb::open_sequence(tmp.str(), "helipr", options);
  EXPECT_TRUE(src->info().poses.empty());
  expect_points(src->points(0), points);

  options.sensor = "Ouster";
  const std::string scan = (tmp / "LiDAR" / "Ouster" / "1692000000000000000.bin").string();
  Bytes b = helipr_points("Ouster", false, {{1, 2, 3}, {4, 5, 6}});
  b.data.resize(30);
  b.write(scan);
  src = vb::open_sequence(tmp.str(), "helipr", options);
  expect_error([&] { src->points(0); }, {scan, "30 bytes", "26-byte"});
  helipr_points("Ouster", false, {{1, 2, 3}, {4, 5, std::nanf("")}}).write(scan);
  expect_error([&] { src->points(0); }, {scan, "byte 34", "field z"});
}

// ---------------------------------------------------------------------------------------------
// nclt

namespace {

Bytes nclt_points(const std::vector<std::array<unsigned, 3>>& stored) {
  Bytes b;
  for (const auto& s : stored) b.u16(s[0]).u16(s[1]).u16(s[2]).u8(77).u8(3);
  return b;
}

}  // namespace

TEST(NcltSource, ScalesRecordsAndTurnsBodyPosesIntoZUpVelodynePoses) {
  TempDir tmp;
  const fs::path seq = tmp / "2012-01-08";
  // Stored 20200 20400 19400 -> (1, 2, -3) m in the z-down Velodyne frame.
  const std::vector<std::array<unsigned, 3>> stored = {{20200, 20400, 19400}, {0, 65535, 20000}};
  const std::vector<Eigen::Vector3f> raw = {{1, 2, -3}, {-100, 227.675f, 0}};
  nclt_points(stored).write(seq / "velodyne_sync" / "1326030975726043.bin");
  nclt_points(stored).write(seq / "velodyne_sync" / "1326030975826043.bin");
  const std::string gt_path = (seq / "groundtruth_2012-01-08.csv").string();
  write_text(gt_path,
             "1326030975700000,nan,nan,nan,nan,nan,nan\n"
             "1326030975726000,10,-5,-0.5,0.01,0.02,1.2\n"
             "1326030975826100,11,-5.5,-0.6,0.02,0.01,1.3\n");
  const auto src = vb::open_sequence(seq.string(), "");
  const auto& info = src->info();
  EXPECT_EQ(info.format, "nclt");
  ASSERT_EQ(src->size(), 2);
  EXPECT_NEAR(info.stamps[0], 1326030975.726043, 1e-6);
  const vb::Cloud points = src->points(0);
  ASSERT_EQ(points.size(), 2u);
  // z up: y and z negated.
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(points[i].x(), raw[i].x(), 1e-4);
    EXPECT_NEAR(points[i].y(), -raw[i].y(), 1e-4);
    EXPECT_NEAR(points[i].z(), -raw[i].z(), 1e-4);
  }
  // A point goes to the same place through our pose as through the body pose and the extrinsic
  // in the z-down world (then flipped).
  constexpr double kDeg = M_PI / 180;
  const vb::Rigid<3> X =
      pose_rpy(0.002, -0.004, -0.957, 0.807 * kDeg, 0.166 * kDeg, -90.703 * kDeg);
  const vb::Rigid<3> G[2] = {pose_rpy(10, -5, -0.5, 0.01, 0.02, 1.2),
                             pose_rpy(11, -5.5, -0.6, 0.02, 0.01, 1.3)};
  ASSERT_EQ(info.poses.size(), 2u);
  for (int s = 0; s < 2; ++s) {
    for (int i = 0; i < 2; ++i) {
      const Eigen::Vector3d ned = G[s] * X * raw[i].cast<double>();
      const Eigen::Vector3d ours = info.poses[s] * points[i].cast<double>();
      EXPECT_LT((ours - Eigen::Vector3d(ned.x(), -ned.y(), -ned.z())).norm(), 1e-3);
    }
  }
  expect_detected_as(seq.string(), "nclt");

  // KISS-ICP's place for the ground truth: ../ground_truth/groundtruth_<date>.csv.
  fs::create_directories(tmp / "ground_truth");
  fs::rename(gt_path, tmp / "ground_truth" / "groundtruth_2012-01-08.csv");
  EXPECT_EQ(vb::open_sequence(seq.string(), "nclt")->info().poses.size(), 2u);

  const std::string bad = (tmp / "ground_truth" / "groundtruth_2012-01-08.csv").string();
  write_text(bad, "1326030975726000,10,-5,-0.5,0.01,0.02\n");
  expect_error([&] { vb::open_sequence(seq.string(), "nclt"); }, {bad + ":1", "6 fields"});
  write_text(bad, "1326030975726000,10,-5,-0.5,0.01,0.02,1.2\n1326030975826100,11,y,0,0,0,0\n");
  expect_error([&] { vb::open_sequence(seq.string(), "nclt"); }, {bad + ":2", "field 3 (y) 'y'"});
  const std::string scan = (seq / "velodyne_sync" / "1326030975726043.bin").string();
  Bytes b = nclt_points(stored);
  b.data.resize(12);
  b.write(scan);
  fs::remove(bad);
  expect_error([&] { vb::open_sequence(seq.string(), "nclt")->points(0); },
               {scan, "12 bytes", "8-byte"});
}

// ---------------------------------------------------------------------------------------------
// carmen

namespace {

std::string flaser(const std::vector<double>& ranges, double x, double y, double theta,
                   const std::string& ipc, const std::string& logger) {
  std::ostringstream s;
  s << "FLASER " << ranges.size();
  for (double r : ranges) s << " " << r;
  s << " " << x << " " << y << " " << theta << " " << x << " " << y << " " << theta << " " << ipc
    << " nohost " << logger << "\n";
  return s.str();
}

}  // namespace

TEST(CarmenSource, TurnsFlaserRangesIntoPlanarPointsWithOdometry) {
  TempDir tmp;
  const std::string log = (tmp / "run.clf").string();
  std::vector<double> wide(180, 0.0);
  wide[0] = 2.0;      // -90 deg
  wide[90] = 3.0;     // 1 deg apart: 0 deg
  wide[179] = 81.83;  // no return
  write_text(log,
             "# message_name [message contents] ipc_timestamp ipc_hostname logger_timestamp\n"
             "PARAM robot_frontlaser_offset 0.0 nohost 0\n"
             "ODOM 0 0 0 0 0 0 100.0 nohost 0.0\n" +
                 flaser({1.0, 2.0, 0.0, 81.0}, 0, 0, 0, "100.05", "0.05") +
                 flaser({4.0, 1.0, 1.0, 2.0}, 1.5, -0.5, 0.25, "100.25", "0.25") +
                 flaser(wide, 2, 1, -3.0, "100.45", "0.45"));
  const auto src = vb::open_sequence(log, "");
  const auto& info = src->info();
  EXPECT_EQ(info.format, "carmen");
  EXPECT_TRUE(info.planar);
  ASSERT_EQ(src->size(), 3);
  EXPECT_EQ(info.stamps, (std::vector<double>{100.05, 100.25, 100.45}));
  EXPECT_TRUE(info.poses.empty());
  ASSERT_EQ(info.odometry.size(), 3u);
  expect_pose_near(info.odometry[1], vb::test::planar_pose(1.5, -0.5, 0.25), 1e-12);
  // Four readings span 180 deg: -90, -30, 30, 90; 0 and >= 80 m are no return.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  const auto f = [](double v) { return static_cast<float>(v); };
  expect_points(src->points(0), {{0, -1, 0}, {f(2 * c), f(-2 * s), 0}}, 1e-6f);
  expect_points(src->points(1), {{0, -4, 0}, {f(c), f(-s), 0}, {f(c), f(s), 0}, {0, 2, 0}}, 1e-6f);
  expect_points(src->points(2), {{0, -2, 0}, {3, 0, 0}}, 1e-6f);
  expect_detected_as(log, "carmen");
  expect_detected_as(tmp.str(), "carmen");  // a folder holding one log

  write_text(log,
             flaser({1.0, 2.0}, 0, 0, 0, "1", "1") + "FLASER 3 1 x 2 0 0 0 0 0 0 5 nohost 5\n");
  expect_error([&] { vb::open_sequence(log, "carmen"); }, {log + ":2", "(range 2) 'x'"});
  write_text(log, "FLASER 3 1 2 0 0 0 0 0 0 5 nohost 5\n");  // 2 ranges, not 3
  expect_error([&] { vb::open_sequence(log, "carmen"); }, {log + ":1", "(ipc_timestamp) 'nohost'"});
  write_text(log, "FLASER 2 1 2 0 0 0 0 0 0 5 nohost 5 7\n");
  expect_error([&] { vb::open_sequence(log, "carmen"); },
               {log + ":1", "1 field(s) after logger_timestamp"});
}

TEST(CarmenSource, KeepsTheScansACorrectedLogMatchesByPrintedStampAndRanges) {
  TempDir tmp;
  const std::string raw = (tmp / "raw.clf").string(), ref = (tmp / "corrected.log").string();
  // Two raw scans 1 ms apart print alike with 6 significant digits: their ranges tell them apart.
  write_text(raw, flaser({1, 1}, 0, 0, 0, "976052857.400000", "0.062716") +
                      flaser({2, 2}, 0.1, 0, 0.01, "976052858.600000", "1001.291000") +
                      flaser({3, 3}, 0.2, 0, 0.02, "976052858.601163", "1001.292163") +
                      flaser({4, 4}, 0.3, 0, 0.03, "976052859.000000", "1001.700000"));
  write_text(ref, "NEFF 15\n" + flaser({3, 3}, 5, 6, 0.5, "1001.29", "1001.29") +
                      flaser({1, 1}, 7, 8, 0.7, "0.0627160", "0.0627160"));
  vb::SourceOptions options;
  options.reference = ref;
  const auto src = vb::open_sequence(raw, "carmen", options);
  const auto& info = src->info();
  ASSERT_EQ(src->size(), 2);
  EXPECT_EQ(info.recorded, 4);
  EXPECT_EQ(info.poses_file, ref);
  EXPECT_NE(info.note.find("kept the 2 of 4"), std::string::npos) << info.note;
  EXPECT_DOUBLE_EQ(info.stamps[0], 976052857.4);
  EXPECT_DOUBLE_EQ(info.stamps[1], 976052858.601163);
  expect_pose_near(info.poses[0], vb::test::planar_pose(7, 8, 0.7), 1e-12);
  expect_pose_near(info.poses[1], vb::test::planar_pose(5, 6, 0.5), 1e-12);
  expect_pose_near(info.odometry[1], vb::test::planar_pose(0.2, 0, 0.02), 1e-12);
  EXPECT_NEAR(src->points(1)[0].y(), -3.0, 1e-6);

  write_text(ref, flaser({9, 9}, 5, 6, 0.5, "1001.29", "1001.29"));
  expect_error([&] { vb::open_sequence(raw, "carmen", options); },
               {ref + ":1", "1001.29", "meets 2 scans", "0 of them by ranges"});
}

TEST(CarmenSource, ReadsTheRealAcesLog) {
  const std::string path = std::string(VERIFYBENCH_SHARED_DATA) + "/radish2d/aces.clf";
  if (!fs::exists(path)) GTEST_SKIP() << path << " is not there (../shared/data)";
  std::ifstream in(path);
  int flaser_lines = 0;
  for (std::string line; std::getline(in, line);) flaser_lines += line.rfind("FLASER ", 0) == 0;
  const auto src = vb::open_sequence(path, "");
  EXPECT_EQ(src->info().format, "carmen");
  EXPECT_EQ(src->size(), flaser_lines);
  EXPECT_EQ(static_cast<int>(src->info().odometry.size()), flaser_lines);
  const auto& t = src->info().stamps;
  for (std::size_t i = 1; i < t.size(); ++i) ASSERT_LE(t[i - 1], t[i]) << "scan " << i;
  EXPECT_GT(src->points(0).size(), 100u);
}

TEST(CarmenSource, MeetsTheRealIntelLogWithItsCorrectedLog) {
  const std::string raw = std::string(VERIFYBENCH_SHARED_DATA) + "/radish2d/intel.clf";
  const std::string ref =
      std::string(VERIFYBENCH_SHARED_DATA) + "/radish2d/corrected/intel-corrected.log";
  if (!fs::exists(raw) || !fs::exists(ref)) GTEST_SKIP() << raw << " or " << ref << " missing";
  vb::SourceOptions options;
  options.reference = ref;
  const auto src = vb::open_sequence(raw, "carmen", options);
  const auto& info = src->info();
  EXPECT_EQ(info.recorded, 13631);
  ASSERT_EQ(src->size(), 910);  // every corrected scan met exactly one raw scan
  EXPECT_EQ(info.poses.size(), 910u);
  EXPECT_EQ(info.odometry.size(), 910u);
  // Met scans moved alike by odometry and by the reference between neighbours (a wrong match
  // would not): the step lengths agree within 10 cm for nearly all.
  int agree = 0;
  for (std::size_t i = 1; i < info.poses.size(); ++i) {
    const double odo = (info.odometry[i].translation() - info.odometry[i - 1].translation()).norm();
    const double ref_step = (info.poses[i].translation() - info.poses[i - 1].translation()).norm();
    agree += std::abs(odo - ref_step) < 0.1;
  }
  EXPECT_GT(agree, 0.95 * 909) << agree;
  for (std::size_t i = 1; i < info.stamps.size(); ++i)
    ASSERT_LE(info.stamps[i - 1], info.stamps[i]);
}

// ---------------------------------------------------------------------------------------------
// the registry

TEST(SequenceRegistry, NamesTheFormatsWhenItCannotChoose) {
  expect_error<std::invalid_argument>([] { vb::open_sequence("/nonexistent", "nope"); },
                                      {"'nope'", "carmen, folder, helipr, kitti, mulran, nclt"});
  TempDir tmp;
  expect_error<std::invalid_argument>([&] { vb::open_sequence(tmp.str(), ""); },
                                      {tmp.str(), "carmen, folder, helipr, kitti, mulran, nclt"});
  // A folder of scans that also holds a KITTI velodyne/ folder matches both.
  kitti_points(kScans[0]).write(tmp / "velodyne" / "000000.bin");
  kitti_points(kScans[0]).write(tmp / "000000.bin");
  expect_error<std::invalid_argument>([&] { vb::open_sequence(tmp.str(), ""); },
                                      {"several", "folder, kitti"});
  EXPECT_EQ(vb::open_sequence(tmp.str(), "kitti")->size(), 1);
  EXPECT_THROW(vb::register_source({"kitti", "", {}, {}}), std::logic_error);
}

// ------------------------------------------------------------------------------------------------
// relations (loop/relations.hpp): Kuemmerle et al.'s reference relations and their error

namespace {

// A planar path along which the pose at sample k is known in closed form: the reference.
vb::Rigid<3> path_pose(int k) {
  return vb::test::planar_pose(0.3 * k + std::sin(0.05 * k), 0.2 * k, 0.02 * k);
}

}  // namespace

TEST(Relations, ReadsTheFileAndNamesEachBadField) {
  TempDir tmp;
  const std::string path = (tmp / "r.relations").string();
  write_text(path, "# t1 t2 x y z roll pitch yaw\n\n90.5 91.0 0.4 -0.1 0 0 0 0.5\n"
                   "1 2 0 0 0 0.1 0 0\n");
  const auto r = vb::read_relations(path);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].t1, 90.5);
  EXPECT_EQ(r[0].t2, 91.0);
  expect_pose_near(r[0].T, vb::test::planar_pose(0.4, -0.1, 0.5), 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(Eigen::Matrix3d(r[1].T.linear())).angle(), 0.1, 1e-12);
  EXPECT_NEAR(r[1].T.linear()(2, 1), std::sin(0.1), 1e-12);  // roll: about x
  write_text(path, "1 2 0 0 0 0 0\n");
  expect_error([&] { vb::read_relations(path); }, {path + ":1", "field yaw missing"});
  write_text(path, "1 2 0 abc 0 0 0 0\n");
  expect_error([&] { vb::read_relations(path); }, {path + ":1", "field y = 'abc' is not a number"});
  write_text(path, "1 2 0 0 0 0 0 0\n1 2 inf 0 0 0 0 0\n");
  expect_error([&] { vb::read_relations(path); }, {path + ":2", "field x = 'inf' is not finite"});
  write_text(path, "3 2 0 0 0 0 0 0\n");
  expect_error([&] { vb::read_relations(path); }, {path + ":1", "is before t1"});
  write_text(path, "1 2 0 0 0 0 0 0 9\n");
  expect_error([&] { vb::read_relations(path); }, {path + ":1", "more than 8 fields"});
  write_text(path, "# nothing\n");
  expect_error([&] { vb::read_relations(path); }, {path, "no relation"});
  expect_error([&] { vb::read_relations((tmp / "none").string()); }, {"cannot open"});
}

TEST(Relations, ErrorIsZeroForTheReferenceAndTheShiftForRelationsAcrossAShiftedPart) {
  // Odometry samples every 0.1 s are the reference path itself; frames are every 10th sample.
  std::vector<double> stamps;
  std::vector<vb::Rigid<3>> odometry;
  for (int k = 0; k <= 200; ++k) {
    stamps.push_back(10.0 + 0.1 * k);
    odometry.push_back(path_pose(k));
  }
  std::vector<double> frame_stamps;
  std::vector<vb::Rigid<3>> exact, shifted;
  const Eigen::Vector3d shift(0.6, -0.8, 0.0);  // |shift| = 1 m
  for (int k = 0; k <= 200; k += 10) {
    frame_stamps.push_back(stamps[static_cast<std::size_t>(k)]);
    exact.push_back(path_pose(k));
    vb::Rigid<3> T = path_pose(k);
    if (k >= 100) T.pretranslate(shift);  // frames from 20 s on moved by 1 m in the world
    shifted.push_back(T);
  }
  // Relations between samples (the reference's own motions), some crossing 20 s, one outside.
  std::vector<vb::Relation> relations;
  int crossing = 0;
  for (int a = 3; a + 37 <= 200; a += 17) {
    const int b = a + 37;
    vb::Relation r;
    r.t1 = stamps[static_cast<std::size_t>(a)];
    r.t2 = stamps[static_cast<std::size_t>(b)];
    r.T = path_pose(a).inverse() * path_pose(b);
    relations.push_back(r);
    // Which side a stamp is on: that of its nearest frame (frames at multiples of 10 samples).
    const auto side = [](int k) { return (k + 5) / 10 * 10 >= 100; };
    crossing += side(a) != side(b);
  }
  vb::Relation outside;
  outside.t1 = 5.0;  // before the odometry
  outside.t2 = 11.0;
  outside.T = vb::Rigid<3>::Identity();
  relations.push_back(outside);
  ASSERT_GT(crossing, 0);

  const vb::RelationError e0 = vb::relation_error(relations, frame_stamps, exact, stamps, odometry);
  EXPECT_EQ(e0.relations, static_cast<int>(relations.size()));
  EXPECT_EQ(e0.used, static_cast<int>(relations.size()) - 1);
  EXPECT_NEAR(e0.translation_m, 0.0, 1e-9);
  EXPECT_NEAR(e0.rotation_deg, 0.0, 1e-6);
  // A relation across the shift errs by x2^-1 (shift) x2: 1 m, no rotation; the others by 0.
  const vb::RelationError e1 =
      vb::relation_error(relations, frame_stamps, shifted, stamps, odometry);
  EXPECT_NEAR(e1.translation_m, 1.0 * crossing / e1.used, 1e-9);
  EXPECT_NEAR(e1.translation_sq, 1.0 * crossing / e1.used, 1e-9);
  EXPECT_NEAR(e1.rotation_deg, 0.0, 1e-6);
  // Between samples the odometry is interpolated: a relation at 10.05 s -> 10.15 s of the
  // straight-line motion between samples 0 and 2 (the reference here is linear in between).
  std::vector<vb::Rigid<3>> line;
  for (int k = 0; k <= 200; ++k) line.push_back(vb::test::planar_pose(0.5 * k, 0, 0));
  vb::Relation half;
  half.t1 = 10.05;
  half.t2 = 10.15;
  half.T = vb::test::planar_pose(0.5, 0, 0);
  const vb::RelationError e2 = vb::relation_error({half}, {10.0}, {line[0]}, stamps, line);
  EXPECT_EQ(e2.used, 1);
  EXPECT_NEAR(e2.translation_m, 0.0, 1e-9);
  EXPECT_THROW(vb::relation_error(relations, frame_stamps, exact, {1.0}, {odometry[0]}),
               std::invalid_argument);
}

TEST(CarmenSource, KeepsTheWholeOdometryStreamForRelations) {
  TempDir tmp;
  const std::string log = (tmp / "run.clf").string();
  write_text(log, flaser({1.0, 2.0}, 0, 0, 0, "100.25", "0.25") +
                      flaser({1.0, 2.0}, 1.5, -0.5, 0.25, "100.05", "0.05"));
  const auto src = vb::open_sequence(log, "carmen");
  const auto& info = src->info();
  EXPECT_EQ(info.odometry_stream_stamps, (std::vector<double>{100.05, 100.25}));  // sorted
  ASSERT_EQ(info.odometry_stream.size(), 2u);
  expect_pose_near(info.odometry_stream[0], vb::test::planar_pose(1.5, -0.5, 0.25), 1e-12);
}
