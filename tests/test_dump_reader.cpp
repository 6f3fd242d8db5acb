// The text dump reader: clear errors on malformed input; the real 3DMatch dump when present.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "cliques/max_clique.hpp"
#include "datasets/dump_format.hpp"
#include "datasets/text_dump.hpp"
#include "graph/compatibility_graph.hpp"

namespace verifybench {
namespace {

namespace fs = std::filesystem;

class DumpReader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("vb_dump_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  std::string error() {
    try {
      read_text_dump(dir_.string());
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(DumpReader, Reads3DWithLabelsAndGroundTruth) {
  write("corr.txt", "# comment\n0 0 0 1 0 0\n\n1 0 0 2 0 0\n0 1 0 1 1 0\n");
  write("label.txt", "1\n1\n0\n");
  write("GTmat.txt", "1 0 0 1\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
  const auto set = std::get<LabeledSet<3>>(read_text_dump(dir_.string()));
  ASSERT_EQ(set.corr.size(), 3);
  EXPECT_EQ(set.corr.target(0, 1), 2.0);
  EXPECT_EQ(set.truth.labels, (std::vector<std::uint8_t>{1, 1, 0}));
  ASSERT_TRUE(set.truth.T_target_source.has_value());
  EXPECT_EQ(set.truth.T_target_source->translation().x(), 1.0);
}

TEST_F(DumpReader, Reads2DFromFourColumns) {
  write("corr.txt", "0 0 1 1\n2 0 3 1\n");
  const auto set = std::get<LabeledSet<2>>(read_text_dump(dir_.string()));
  EXPECT_EQ(set.corr.size(), 2);
  EXPECT_TRUE(set.truth.labels.empty());
  EXPECT_FALSE(set.truth.T_target_source.has_value());
}

TEST_F(DumpReader, NamesFileLineAndFieldOfABadNumber) {
  write("corr.txt", "0 0 0 1 0 0\n0 0 0 1 x7 0\n");
  const std::string e = error();
  EXPECT_NE(e.find("corr.txt:2"), std::string::npos) << e;
  EXPECT_NE(e.find("column 5"), std::string::npos) << e;
  EXPECT_NE(e.find("'x7'"), std::string::npos) << e;
}

TEST_F(DumpReader, RejectsNonFiniteValues) {
  write("corr.txt", "0 0 0 1 0 0\n0 0 nan 1 0 0\n");
  EXPECT_NE(error().find("corr.txt:2: field column 3: 'nan' is not finite"), std::string::npos)
      << error();
  write("corr.txt", "0 0 0 1 0 inf\n");
  EXPECT_NE(error().find("corr.txt:1"), std::string::npos);
}

TEST_F(DumpReader, RejectsRaggedRowsAndWrongWidths) {
  write("corr.txt", "0 0 0 1 0 0\n0 0 0 1 0\n");
  EXPECT_NE(error().find("corr.txt:2: expected 6 fields"), std::string::npos) << error();
  write("corr.txt", "0 0 0\n");
  EXPECT_NE(error().find("expected 6 fields (xs ys zs xt yt zt) or 4"), std::string::npos)
      << error();
}

TEST_F(DumpReader, RejectsEmptyAndMissingFiles) {
  write("corr.txt", "# nothing\n\n");
  EXPECT_NE(error().find("no correspondences"), std::string::npos) << error();
  fs::remove(dir_ / "corr.txt");
  EXPECT_NE(error().find("corr.txt: missing"), std::string::npos) << error();
  EXPECT_THROW(read_text_dump((dir_ / "nope").string()), InputError);
}

// Ground truth as datasets print it: |R^T R - I| up to 1e-2 is projected onto SO(3) and recorded;
// beyond, or a reflection, is refused with the value and the limit.
TEST_F(DumpReader, GroundTruthToleranceIsOneHundredthAndProjectsOntoSO3) {
  write("corr.txt", "0 0 0 1 0 0\n1 0 0 2 0 0\n");
  // R = diag(1 + d, 1, 1): |R^T R - I|_F = 2d + d^2.
  auto gt_with = [&](double d) {
    std::ostringstream m;
    m.precision(17);
    m << 1 + d << " 0 0 0.5\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
    write("GTmat.txt", m.str());
  };
  const double d_in = 0.0049;  // residual 0.00982
  gt_with(d_in);
  const auto set = std::get<LabeledSet<3>>(read_text_dump(dir_.string()));
  const Eigen::Matrix3d R = set.truth.T_target_source->linear();
  EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(R(0, 0), 1.0, 1e-12);  // the nearest rotation to diag(1 + d, 1, 1) is I
  EXPECT_NEAR(set.truth.rotation_residual, 2 * d_in + d_in * d_in, 1e-12);
  EXPECT_EQ(set.truth.T_target_source->translation()(0), 0.5);
  gt_with(0.0051);  // residual 0.01023: over the limit
  EXPECT_NE(error().find("limit 0.01"), std::string::npos) << error();
  EXPECT_NE(error().find("GTmat.txt"), std::string::npos) << error();
  write("GTmat.txt", "-1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");  // a reflection
  EXPECT_NE(error().find("det = -1"), std::string::npos) << error();
}

TEST_F(DumpReader, RejectsMismatchedLabelsAndBadGroundTruth) {
  write("corr.txt", "0 0 0 1 0 0\n1 0 0 2 0 0\n");
  write("label.txt", "1\n");
  EXPECT_NE(error().find("has 1 labels but corr.txt has 2"), std::string::npos) << error();
  write("label.txt", "1\n2\n");
  EXPECT_NE(error().find("label.txt:2"), std::string::npos) << error();
  write("label.txt", "1\n0\n");
  write("GTmat.txt", "2 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n");
  EXPECT_NE(error().find("not a rotation"), std::string::npos) << error();
  write("GTmat.txt", "1 0 0 0\n0 1 0 0\n0 0 1 0\n");
  EXPECT_NE(error().find("expected a 4x4 matrix"), std::string::npos) << error();
}

TEST(DumpFormat, RoundTripsEveryField) {
  LabeledSet<3> s;
  s.corr.source = Eigen::Matrix3Xd::Random(3, 7) * 50;
  s.corr.target = Eigen::Matrix3Xd::Random(3, 7) * 50;
  s.corr.score = {-1, -2, -3, -4.5, 0, 7, 1e-9};
  s.truth.labels = {1, 0, 1, 0, 0, 1, 1};
  Rigid<3> T = Rigid<3>::Identity();
  T.linear() = Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1, -2, 3);
  s.truth.T_target_source = T;
  Dump d;
  d.set = s;
  d.label_threshold = 0.75;
  d.provenance = {{"tool", "test"}};
  const fs::path dir = fs::temp_directory_path() / "vb_dump_roundtrip";
  fs::remove_all(dir);
  write_dump(dir.string(), d);
  EXPECT_THROW(write_dump(dir.string(), d), std::runtime_error);  // never overwrites
  const Dump back = read_dump(dir.string());
  const auto& b = std::get<LabeledSet<3>>(back.set);
  EXPECT_TRUE(b.corr.source.isApprox(s.corr.source, 1e-15));
  EXPECT_TRUE(b.corr.target.isApprox(s.corr.target, 1e-15));
  EXPECT_EQ(b.corr.score, s.corr.score);
  EXPECT_EQ(b.truth.labels, s.truth.labels);
  EXPECT_TRUE(b.truth.T_target_source->isApprox(T, 1e-12));
  EXPECT_EQ(*back.label_threshold, 0.75);
  EXPECT_EQ(back.provenance["tool"], "test");
  // A corrupted row names file, line and field.
  {
    std::ofstream out(dir / "matches.tsv", std::ios::app);
    out << "1\t2\t3\t4\t5\tsix\t0\t1\n";
  }
  try {
    read_dump(dir.string());
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("matches.tsv"), std::string::npos) << m;
    EXPECT_NE(m.find("line 9"), std::string::npos) << m;
    EXPECT_NE(m.find("zt = 'six'"), std::string::npos) << m;
  }
  // A header from the future, a count that disagrees, and no JSON at all are named too.
  auto expect_error = [&](const std::string& json_text, const std::string& needle) {
    std::ofstream(dir / "dump.json") << json_text;
    try {
      read_dump(dir.string());
      FAIL() << json_text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("dump.json"), std::string::npos) << e.what();
    }
  };
  expect_error(R"({"format": "verifybench-dump", "version": 2, "dim": 3})", "version = 2");
  expect_error(R"({"format": "verifybench-dump", "version": 1, "dim": 4})", "dim = 4");
  expect_error(R"({"format": "something-else", "version": 1})", "format");
  expect_error("{not json", "not valid JSON");
  expect_error(R"({"format": "verifybench-dump", "version": 1, "dim": 2,
                   "columns": ["xs", "ys", "zs", "xt", "yt", "zt"]})",
               "columns do not match dim 2");
  // 64-bit values are not truncated to 32 bits (4294967297 is not version 1 or dim 3 ...).
  expect_error(R"({"format": "verifybench-dump", "version": 4294967297, "dim": 3})",
               "version = 4294967297");
  expect_error(R"({"format": "verifybench-dump", "version": 1, "dim": 4294967299})",
               "dim = 4294967299");
  // ... a field of the wrong JSON type is an input error naming the file, not a library message ...
  expect_error(R"({"format": "verifybench-dump", "version": 1, "dim": 3, "columns": "xs"})",
               "dump.json");
  // ... and deep nesting or a huge metadata file is refused before it is copied.
  expect_error(R"({"format": "verifybench-dump", "version": 1, "dim": 3, "provenance": )" +
                   std::string(100000, '[') + std::string(100000, ']') + "}",
               "nesting deeper than 64");
  expect_error(R"({"format": "verifybench-dump", "version": 1, "dim": 3, "pad": ")" +
                   std::string(17u << 20, 'x') + "\"}",
               "metadata only");
  fs::remove_all(dir);
}

TEST(DumpFormat, AnEmptyDumpIsRefusedAsTheTextReaderRefusesOne) {
  LabeledSet<3> s;
  s.corr.source = Eigen::Matrix3Xd::Random(3, 2);
  s.corr.target = s.corr.source;
  Dump d;
  d.set = s;
  const fs::path dir = fs::temp_directory_path() / "vb_dump_empty";
  fs::remove_all(dir);
  write_dump(dir.string(), d);
  {
    std::ifstream in(dir / "matches.tsv");
    std::string header;
    std::getline(in, header);
    in.close();
    std::ofstream(dir / "matches.tsv") << header << "\n";  // keep only the header
  }
  nlohmann::json meta;
  {
    std::ifstream in(dir / "dump.json");
    meta = nlohmann::json::parse(in);
  }
  meta["count"] = 0;
  std::ofstream(dir / "dump.json") << meta.dump();
  try {
    read_dump(dir.string());
    ADD_FAILURE() << "an empty dump was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no correspondences"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("matches.tsv"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// The clouds a dump keeps (extract --keep-clouds): written in the KITTI .bin layout and read back
// bit for bit; a damaged or hostile cloud entry is an input error naming the file and the field,
// and a dump without the entry reads as before (no clouds).
TEST(DumpFormat, KeptCloudsRoundTripAndBadOnesAreNamed) {
  LabeledSet<3> s;
  s.corr.source = Eigen::Matrix3Xd::Random(3, 5);
  s.corr.target = Eigen::Matrix3Xd::Random(3, 5);
  Dump d;
  d.set = s;
  DumpClouds c;
  for (int i = 0; i < 9; ++i) c.source.emplace_back(0.5f * i, -1.25f * i, 3.0f + i);
  for (int i = 0; i < 4; ++i) c.target.emplace_back(-7.0f * i, 0.1f, 1e6f);
  c.voxel = 0.25;
  d.clouds = c;
  const fs::path dir = fs::temp_directory_path() / "vb_dump_clouds";
  fs::remove_all(dir);
  write_dump(dir.string(), d);
  // The layout any KITTI reader expects: 16-byte records x y z r.
  EXPECT_EQ(fs::file_size(dir / "source_cloud.bin"), 9u * 16u);
  EXPECT_EQ(fs::file_size(dir / "target_cloud.bin"), 4u * 16u);
  const Dump back = read_dump(dir.string());
  ASSERT_TRUE(back.clouds.has_value());
  EXPECT_EQ(back.clouds->source, c.source);
  EXPECT_EQ(back.clouds->target, c.target);
  EXPECT_EQ(back.clouds->voxel, 0.25);
  nlohmann::json meta;
  {
    std::ifstream in(dir / "dump.json");
    meta = nlohmann::json::parse(in);
  }
  auto expect_error = [&](const nlohmann::json& clouds, const std::string& file,
                          const std::string& needle) {
    nlohmann::json m = meta;
    m["clouds"] = clouds;
    std::ofstream(dir / "dump.json") << m.dump();
    try {
      read_dump(dir.string());
      ADD_FAILURE() << clouds.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
  };
  const nlohmann::json good = meta["clouds"];
  nlohmann::json bad = good;
  bad["points"] = {9, 5};
  expect_error(bad, "target_cloud.bin", "declares 5 points");
  bad = good;
  bad["source"] = "../elsewhere.bin";
  expect_error(bad, "dump.json", "clouds.source");
  bad = good;
  bad["target"] = "/etc/passwd";
  expect_error(bad, "dump.json", "clouds.target");
  bad = good;
  bad["points"] = {0, 4};
  expect_error(bad, "dump.json", "clouds.points[0] = 0");
  bad = good;
  bad["points"] = {1LL << 40, 4};
  expect_error(bad, "dump.json", "clouds.points[0]");
  bad = good;
  bad["source"] = "missing.bin";
  expect_error(bad, "missing.bin", "cannot read");
  expect_error(nlohmann::json("source_cloud.bin"), "dump.json", "clouds is not an object");
  // A non-finite coordinate names its point and field; a torn file is not whole records.
  {
    std::fstream f(dir / "source_cloud.bin", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(2 * 16 + 4);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    f.write(reinterpret_cast<const char*>(&nan), sizeof nan);
  }
  expect_error(good, "source_cloud.bin", "point 2 field y");
  {
    std::fstream f(dir / "source_cloud.bin", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(2 * 16 + 4);
    f.write(reinterpret_cast<const char*>(&c.source[2].y()), sizeof(float));
  }
  fs::resize_file(dir / "target_cloud.bin", 4 * 16 - 3);
  expect_error(good, "target_cloud.bin", "61 bytes");
  // Without the entry: no clouds, as before.
  nlohmann::json plain = meta;
  plain.erase("clouds");
  std::ofstream(dir / "dump.json") << plain.dump();
  EXPECT_FALSE(read_dump(dir.string()).clouds.has_value());
  fs::remove_all(dir);
}

// matches.tsv opens with a tab-separated line of column names (pandas reads it as is); the
// "# xs ys ..." header of earlier dumps is still read.
TEST(DumpFormat, MatchesTsvHasATabSeparatedHeaderAndOldHeadersStillRead) {
  LabeledSet<2> s;
  s.corr.source.resize(2, 3);
  s.corr.target.resize(2, 3);
  s.corr.source << 0, 1, 0, 0, 0, 1;
  s.corr.target << 1, 2, 1, 1, 1, 2;
  s.truth.labels = {1, 0, 1};
  Dump d;
  d.set = s;
  const fs::path dir = fs::temp_directory_path() / "vb_dump_header";
  fs::remove_all(dir);
  write_dump(dir.string(), d);
  std::ifstream in(dir / "matches.tsv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "xs\tys\txt\tyt\tlabel");
  in.close();
  std::ofstream(dir / "matches.tsv") << "# xs ys xt yt label\n0 0 1 1 1\n1 0 2 1 0\n0 1 1 2 1\n";
  const Dump back = read_dump(dir.string());
  const auto& b = std::get<LabeledSet<2>>(back.set);
  ASSERT_EQ(b.corr.size(), 3);
  EXPECT_EQ(b.corr.target(0, 2), 1.0);
  EXPECT_EQ(b.truth.labels, (std::vector<std::uint8_t>{1, 0, 1}));
  fs::remove_all(dir);
}

TEST(RealDump, ThreeDMatch6614HasKnownCliqueNumber) {
  const std::string dir = std::string(VERIFYBENCH_SHARED_DATA) + "/3dmatch/corr_6614";
  if (!fs::exists(dir + "/corr.txt")) GTEST_SKIP() << "shared data absent: " << dir;
  const auto set = std::get<LabeledSet<3>>(read_text_dump(dir));
  EXPECT_EQ(set.corr.size(), 6614);  // the dump's README
  EXPECT_EQ(std::count(set.truth.labels.begin(), set.truth.labels.end(), 1), 85);
  // omega = 60 at eps = 0.1 m, the figure PMC (TEASER++'s solver) gives for this dump.
  const auto g = build_compatibility_graph(set.corr, GraphParams{0.1});
  const auto r = max_clique(g);
  EXPECT_TRUE(r.optimal);
  EXPECT_EQ(r.clique.size(), 60u);
  EXPECT_TRUE(g.is_clique(r.clique));
}

}  // namespace
}  // namespace verifybench
