// The front end against oracles: B-SHOT codes worked out by hand from the rule, HBST against
// brute-force Hamming search, the BEV image of a drawn point set counted by hand, and and
// extraction on a drawn scene with a known motion (the motion is recovered).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <tuple>

#include "acceptance/dense_check.hpp"
#include "core/metrics.hpp"
#include "frontend/bev.hpp"
#include "frontend/bshot.hpp"
#include "frontend/extract.hpp"
#include "frontend/hbst.hpp"
#include "frontend/matching.hpp"
#include "harness/builtin.hpp"
#include "solvers/registry.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

namespace fs = std::filesystem;

TEST(Bshot, CodesFollowTheNinetyPercentRule) {
  struct Case {
    float v[4];
    std::uint8_t code;
  };
  const Case cases[] = {
      {{0, 0, 0, 0}, 0b0000},                  // case A: empty
      {{0.95f, 0.05f, 0, 0}, 0b0001},          // B: v0 holds 95%
      {{0, 0, 1, 0}, 0b0100},                  // B: v2 alone
      {{0.5f, 0.45f, 0.05f, 0}, 0b0011},       // C: v0 + v1 = 95%
      {{0.05f, 0, 0.5f, 0.45f}, 0b1100},       // C: v2 + v3
      {{0.46f, 0.02f, 0.02f, 0.5f}, 0b1001},   // C: v0 + v3 (after 01, 12, 23 fail)
      {{0.48f, 0.03f, 0.46f, 0.03f}, 0b0101},  // C: v0 + v2 (last pair tried)
      {{0.3f, 0.3f, 0.35f, 0.05f}, 0b0111},    // D: v0 + v1 + v2 = 95%
      {{0.02f, 0.33f, 0.33f, 0.32f}, 0b1110},  // D: v1 + v2 + v3 = 98%
      {{0.25f, 0.25f, 0.25f, 0.25f}, 0b1111},  // E: no group of three reaches 90%
  };
  for (const Case& c : cases) {
    EXPECT_EQ(bshot_code(c.v), c.code) << c.v[0] << " " << c.v[1] << " " << c.v[2] << " " << c.v[3];
  }
  // A whole descriptor: group g lands in bits 4g..4g+3, the last 32 bits stay zero.
  float shot[kShotLength] = {};
  shot[0] = 1.0f;                                       // group 0 -> 0001
  shot[4 * 17 + 3] = 2.0f;                              // group 17 -> 1000 at bits 68..71
  for (int k = 0; k < 4; ++k) shot[4 * 87 + k] = 1.0f;  // group 87 -> 1111 at bits 348..351
  std::uint64_t out[6];
  binarize_shot(shot, out);
  EXPECT_EQ(out[0], 0x1u);
  EXPECT_EQ(out[1], std::uint64_t{0x8} << (68 - 64));
  EXPECT_EQ(out[5], std::uint64_t{0xF} << (348 - 320));
  EXPECT_EQ(out[2] | out[3] | out[4], 0u);
}

BinaryDescriptors random_descriptors(int count, int bits, std::mt19937_64& rng, double p_one) {
  BinaryDescriptors d(bits);
  std::bernoulli_distribution one(p_one);
  for (int i = 0; i < count; ++i) {
    auto* row = d.add();
    for (int b = 0; b < bits; ++b) {
      if (one(rng)) row[b / 64] |= std::uint64_t{1} << (b % 64);
    }
  }
  return d;
}

TEST(Hbst, ExactModeIsBruteForceAndLeafModeNeverBeatsIt) {
  std::mt19937_64 rng(7);
  for (int bits : {256, 352}) {
    const auto base = random_descriptors(3000, bits, rng, 0.5);
    // Queries: noisy copies of stored descriptors (some within the threshold) and random ones.
    BinaryDescriptors queries(bits);
    std::uniform_int_distribution<int> pick(0, base.size() - 1), flip(0, bits - 1);
    for (int q = 0; q < 300; ++q) {
      auto* row = queries.add();
      const int from = pick(rng);
      std::copy(base.row(from), base.row(from) + base.words(), row);
      const int flips = q % 3 == 0 ? 200 : q % 60;
      for (int f = 0; f < flips; ++f) {
        const int b = flip(rng);
        row[b / 64] ^= std::uint64_t{1} << (b % 64);
      }
    }
    HbstTree tree(bits, HbstParams{16, 64});
    // Inserted in two batches: incremental insertion splits leaves as they fill.
    BinaryDescriptors first(bits), second(bits);
    first.data.assign(base.data.begin(), base.data.begin() + 1500 * base.words());
    second.data.assign(base.data.begin() + 1500 * base.words(), base.data.end());
    tree.insert(first);
    tree.insert(second);
    ASSERT_EQ(tree.size(), 3000);
    EXPECT_GT(tree.depth(), 4);
    int leaf_hits = 0, truth_hits = 0, near = 0;
    for (int q = 0; q < queries.size(); ++q) {
      const BinaryMatch truth = brute_force_nearest(base, queries.row(q), 50);
      const BinaryMatch exact = tree.nearest(queries.row(q), 50, true);
      EXPECT_EQ(exact.index, truth.index) << "query " << q;
      EXPECT_EQ(exact.distance, truth.distance) << "query " << q;
      const BinaryMatch leaf = tree.nearest(queries.row(q), 50, false);
      if (leaf.index >= 0) {
        EXPECT_GE(leaf.distance, truth.distance);
        EXPECT_LE(leaf.distance, 50);
        EXPECT_EQ(hamming(base.row(leaf.index), queries.row(q), base.words()), leaf.distance);
        if (q % 3 != 0 && q % 60 <= 8) leaf_hits += leaf.index == truth.index;
      }
      truth_hits += truth.index >= 0;
      near += q % 3 != 0 && q % 60 <= 8;
    }
    EXPECT_GT(truth_hits, 100);
    // One leaf misses a copy whenever a flipped bit is one the path splits on: with <= 8 of
    // 256+ bits flipped and a depth near 8, most near copies are still found.
    EXPECT_GT(leaf_hits, near / 2) << leaf_hits << " of " << near;
  }
}

TEST(Bev, CountsAndScalesADrawnPointSet) {
  Cloud cloud;
  for (int k = 0; k < 40; ++k) cloud.emplace_back(0.1f, 0.2f, float(k));  // cell (100, 100): 40
  for (int k = 0; k < 10; ++k) cloud.emplace_back(-0.3f, 0.2f, 0.0f);     // cell (99, 100): 10
  cloud.emplace_back(-49.9f, -49.9f, 0.0f);  // cell (0, 0): 1, under 5% of 40
  cloud.emplace_back(60.0f, 0.0f, 0.0f);     // outside the 50 m window
  const BevImage img = make_bev(cloud, BevParams{});
  ASSERT_EQ(img.size, 200);
  EXPECT_EQ(img.counts[100 * 200 + 100], 40);
  EXPECT_EQ(img.pixels[100 * 200 + 100], 255);
  EXPECT_EQ(img.counts[100 * 200 + 99], 10);
  EXPECT_EQ(img.pixels[100 * 200 + 99], 64);  // round(255 * 10 / 40)
  EXPECT_EQ(img.counts[0], 1);
  EXPECT_EQ(img.pixels[0], 0);  // dropped: 1 < 0.05 * 40
  int total = 0;
  for (int c : img.counts) total += c;
  EXPECT_EQ(total, 51);  // the point outside is not counted
  EXPECT_TRUE(img.metric(100.5, 100.5).isApprox(Eigen::Vector2d(0.25, 0.25)));
  EXPECT_THROW(make_bev(cloud, BevParams{0.0, 0.05, 50}), std::invalid_argument);
  // Extreme range / cell: refused before any conversion to int or allocation.
  EXPECT_THROW(make_bev(cloud, BevParams{1e-9, 0.05, 1e9}), std::invalid_argument);
  EXPECT_THROW(make_bev(cloud, BevParams{0.001, 0.05, 1e4}), std::invalid_argument);  // 2e7 a side
}

/// A street: ground, building blocks with windows (ISS corners), poles, sampled every 0.1 m.
Cloud drawn_street(std::mt19937_64& rng) {
  Cloud c;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double x = -30; x < 30; x += 0.25)
    for (double y = -12; y < 12; y += 0.25) c.emplace_back(x + 0.05 * u(rng), y, -1.7f);
  for (int b = 0; b < 10; ++b) {  // blocks along both sides, different sizes
    const double x0 = -28 + 6 * b + 2 * u(rng), side = b % 2 ? 8.0 : -8.0;
    const double w = 2 + 3 * u(rng), h = 3 + 6 * u(rng), depth = 1.5 + 2 * u(rng);
    for (double x = x0; x < x0 + w; x += 0.1)
      for (double z = -1.7; z < h; z += 0.1) {
        c.emplace_back(x, side, z);
        c.emplace_back(x, side + (side > 0 ? depth : -depth), z);
      }
    for (double y = 0; y < depth; y += 0.1)
      for (double z = -1.7; z < h; z += 0.1) {
        c.emplace_back(x0, side + (side > 0 ? y : -y), z);
        c.emplace_back(x0 + w, side + (side > 0 ? y : -y), z);
      }
  }
  for (int p = 0; p < 12; ++p) {  // poles
    const double x = -27 + 4.7 * p, y = (p % 2 ? 5.0 : -5.0) + u(rng);
    for (double z = -1.7; z < 3 + u(rng); z += 0.05) c.emplace_back(x, y, z);
  }
  return c;
}

Cloud moved(const Cloud& c, const Rigid<3>& T, std::mt19937_64& rng, double noise) {
  std::normal_distribution<double> g(0.0, noise);
  Cloud out;
  out.reserve(c.size());
  for (const auto& p : c) {
    const Eigen::Vector3d q = T * p.cast<double>() + Eigen::Vector3d(g(rng), g(rng), g(rng));
    out.push_back(q.cast<float>());
  }
  return out;
}

TEST(Extract, RecoversAKnownMotionFromADrawnStreet3D) {
  register_builtin_solvers();
  std::mt19937_64 rng(3);
  const Cloud source = drawn_street(rng);
  Rigid<3> T = Rigid<3>::Identity();
  T.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1.5, -0.8, 0.1);
  const Cloud target = moved(source, T, rng, 0.01);
  ExtractParams p;
  const Features fs = extract_features(source, p), ft = extract_features(target, p);
  EXPECT_GT(fs.counts.at("keypoints"), 20);
  EXPECT_EQ(fs.descriptors.size(), static_cast<int>(fs.points.size()));
  const Dump dump = match_features(fs, ft, T, p);
  const auto& set = std::get<LabeledSet<3>>(dump.set);
  const int labelled =
      static_cast<int>(std::count(set.truth.labels.begin(), set.truth.labels.end(), 1));
  EXPECT_GE(labelled, 5);
  SolverParams sp;
  sp.eps = 1.0;
  sp.inlier_threshold = 1.0;
  const auto r = SolverRegistry::create("clique")->solve(set.corr, sp);
  ASSERT_TRUE(r.accepted);
  EXPECT_LT(rotation_error_deg(r.T_target_source, T), 2.0);
  EXPECT_LT(translation_error(r.T_target_source, T), 0.5);
}

// `extract` keeps both scans by default, one point per occupied 0.25 m cell (counted here from
// the points), every point at --cloud-voxel 0, and none with --no-clouds.
TEST(Extract, KeepsTheCloudsOnTheirGridUnlessTold) {
  std::mt19937_64 rng(4);
  const Cloud source = drawn_street(rng);
  Rigid<3> T = Rigid<3>::Identity();
  T.translation() = Eigen::Vector3d(1.0, 0.5, 0.0);
  const Cloud target = moved(source, T, rng, 0.01);
  const fs::path root = fs::temp_directory_path() / "vb_extract_clouds";
  fs::remove_all(root);
  fs::create_directories(root);
  auto write_bin = [&](const Cloud& c, const std::string& name) {
    std::ofstream out(root / name, std::ios::binary);
    for (const auto& p : c) {
      const float r[4] = {p.x(), p.y(), p.z(), 0.0f};
      out.write(reinterpret_cast<const char*>(r), sizeof r);
    }
  };
  write_bin(source, "s.bin");
  write_bin(target, "t.bin");
  auto extract_to = [&](const std::string& name, const std::string& extra) {
    const auto r = test::run_cli("extract --pipeline fpfh --voxel 0.5 --matching mutual --source " +
                                 (root / "s.bin").string() + " --target " +
                                 (root / "t.bin").string() + " " + extra + " --out " +
                                 (root / name).string());
    EXPECT_EQ(r.code, 0) << r.output;
    return read_dump((root / name).string());
  };
  auto cells = [](const Cloud& c, float leaf) {
    std::set<std::array<long long, 3>> occupied;
    for (const auto& p : c) {
      occupied.insert({static_cast<long long>(std::floor(p.x() / leaf)),
                       static_cast<long long>(std::floor(p.y() / leaf)),
                       static_cast<long long>(std::floor(p.z() / leaf))});
    }
    return static_cast<double>(occupied.size());
  };
  const Dump kept = extract_to("kept", "");
  ASSERT_TRUE(kept.clouds.has_value());
  EXPECT_EQ(kept.clouds->voxel, 0.25);
  EXPECT_NEAR(static_cast<double>(kept.clouds->source.size()), cells(source, 0.25f),
              0.002 * cells(source, 0.25f));
  EXPECT_NEAR(static_cast<double>(kept.clouds->target.size()), cells(target, 0.25f),
              0.002 * cells(target, 0.25f));
  const Dump all = extract_to("all", "--cloud-voxel 0");
  ASSERT_TRUE(all.clouds.has_value());
  EXPECT_EQ(all.clouds->source, source);
  EXPECT_EQ(all.clouds->target, target);
  const Dump none = extract_to("none", "--no-clouds");
  EXPECT_FALSE(none.clouds.has_value());
  EXPECT_FALSE(fs::exists(root / "none" / "source_cloud.bin"));
  fs::remove_all(root);
}

TEST(Extract, RecoversAKnownMotionFromADrawnStreet2D) {
  register_builtin_solvers();
  std::mt19937_64 rng(4);
  const Cloud source = drawn_street(rng);
  Rigid<3> T = Rigid<3>::Identity();
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(2.0, 1.0, 0.0);
  const Cloud target = moved(source, T, rng, 0.01);
  ExtractParams p;
  p.pipeline = "2d";
  const Dump dump = match_features(extract_features(source, p), extract_features(target, p), T, p);
  const auto& set = std::get<LabeledSet<2>>(dump.set);
  SolverParams sp;
  sp.eps = 1.0;
  sp.inlier_threshold = 1.0;
  const auto r = SolverRegistry::create("clique")->solve(set.corr, sp);
  ASSERT_TRUE(r.accepted) << r.inliers.size() << " inliers of " << set.corr.size();
  Rigid<2> T2 = Rigid<2>::Identity();
  T2.linear() = Eigen::Rotation2Dd(0.3).toRotationMatrix();
  T2.translation() = Eigen::Vector2d(2.0, 1.0);
  EXPECT_LT(rotation_error_deg(r.T_target_source, T2), 2.0);
  EXPECT_LT(translation_error(r.T_target_source, T2), 0.5);
}

// Matching policies against their definitions, worked out from the full distance matrix.
template <class Distance>
std::vector<FeatureMatch> by_definition(int ns, int nt, Distance dist, const MatchingPolicy& p,
                                        double max_d) {
  std::vector<FeatureMatch> out;
  auto nearest_target = [&](int i) {
    int best = -1;
    for (int j = 0; j < nt; ++j)
      if (best < 0 || dist(i, j) < dist(i, best)) best = j;
    return best;
  };
  auto nearest_source = [&](int j) {
    int best = -1;
    for (int i = 0; i < ns; ++i)
      if (best < 0 || dist(i, j) < dist(best, j)) best = i;
    return best;
  };
  for (int i = 0; i < ns; ++i) {
    std::vector<FeatureMatch> row;
    for (int j = 0; j < nt; ++j) row.push_back({i, j, dist(i, j)});
    std::stable_sort(row.begin(), row.end(),
                     [](const auto& a, const auto& b) { return a.distance < b.distance; });
    const int keep = p.kind == MatchingPolicy::Kind::knn      ? p.k
                     : p.kind == MatchingPolicy::Kind::radius ? nt
                                                              : 1;
    // Lowe's test: the nearest only when the second nearest within max_d is farther than d1 / R.
    if (p.kind == MatchingPolicy::Kind::ratio && nt >= 2 && row[1].distance <= max_d &&
        !(row[0].distance < p.ratio * row[1].distance)) {
      continue;
    }
    for (int r = 0; r < std::min(keep, nt); ++r) {
      const FeatureMatch& m = row[static_cast<std::size_t>(r)];
      if (m.distance > max_d) break;
      if (p.kind == MatchingPolicy::Kind::nearest && m.target != nearest_target(i)) continue;
      if (p.kind == MatchingPolicy::Kind::mutual && nearest_source(m.target) != i) continue;
      out.push_back(m);
    }
  }
  return out;
}

void expect_same(const std::vector<FeatureMatch>& got, const std::vector<FeatureMatch>& want,
                 const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_EQ(got[k].source, want[k].source) << what << " #" << k;
    EXPECT_EQ(got[k].target, want[k].target) << what << " #" << k;
    EXPECT_NEAR(got[k].distance, want[k].distance, 1e-4) << what << " #" << k;
  }
}

TEST(Matching, EveryPolicyMatchesItsDefinitionForBinaryAndFpfh) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 10.0f);
  RealDescriptors rs, rt;
  rs.dims = rt.dims = 33;
  for (int k = 0; k < 60 * 33; ++k) rs.data.push_back(u(rng));
  for (int k = 0; k < 80 * 33; ++k) rt.data.push_back(u(rng));
  BinaryDescriptors bs(96), bt(96);
  for (int k = 0; k < 60; ++k) {
    std::uint64_t* r = bs.add();
    r[0] = rng(), r[1] = rng() & 0xffffffffu;
  }
  for (int k = 0; k < 80; ++k) {
    std::uint64_t* r = bt.add();
    r[0] = rng(), r[1] = rng() & 0xffffffffu;
  }
  auto l2 = [&](int i, int j) {
    double d = 0;
    for (int b = 0; b < 33; ++b) d += std::pow(double(rs.row(i)[b]) - rt.row(j)[b], 2);
    return std::sqrt(d);
  };
  // Hamming ties are common: the definition's stable sort keeps the lower target first, as the
  // matcher must; ties of the nearest source go to the lower source.
  auto ham = [&](int i, int j) { return double(hamming(bs.row(i), bt.row(j), bs.words())); };
  for (const char* text : {"nearest", "mutual", "knn:3", "radius", "ratio:0.9", "ratio:0.97"}) {
    const MatchingPolicy p = parse_matching(text);
    EXPECT_EQ(p.name(), text);
    const double radius = 20.0;
    expect_same(match_real(rs, rt, p, radius), by_definition(60, 80, l2, p, radius),
                std::string("fpfh ") + text);
    expect_same(match_binary(bs, bt, p, 40), by_definition(60, 80, ham, p, 40),
                std::string("binary ") + text);
  }
  EXPECT_THROW(parse_matching("knn:0"), std::invalid_argument);
  EXPECT_THROW(parse_matching("ratio:0"), std::invalid_argument);
  EXPECT_THROW(parse_matching("ratio:1.5"), std::invalid_argument);
  EXPECT_THROW(parse_matching("closest"), std::invalid_argument);
}

TEST(Extract, FpfhRecoversAKnownMotionFromADrawnStreet) {
  register_builtin_solvers();
  std::mt19937_64 rng(5);
  const Cloud source = drawn_street(rng);
  Rigid<3> T = Rigid<3>::Identity();
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1.0, 0.5, 0.0);
  const Cloud target = moved(source, T, rng, 0.01);
  ExtractParams p;
  p.pipeline = "fpfh";
  p.pf.voxel = 0.3;
  p.matching = parse_matching("mutual");
  p.label_threshold = 0.6;
  const Features fs = extract_features(source, p), ft = extract_features(target, p);
  EXPECT_EQ(fs.real.size(), static_cast<int>(fs.points.size()));
  EXPECT_GT(fs.real.size(), 100);
  const Dump dump = match_features(fs, ft, T, p);
  EXPECT_EQ(dump.provenance["matcher"]["policy"], "mutual");
  const auto& set = std::get<LabeledSet<3>>(dump.set);
  SolverParams sp;
  sp.eps = 0.6;
  sp.inlier_threshold = 0.6;
  const auto r = SolverRegistry::create("clique")->solve(set.corr, sp);
  ASSERT_TRUE(r.accepted);
  EXPECT_LT(rotation_error_deg(r.T_target_source, T), 2.0);
  EXPECT_LT(translation_error(r.T_target_source, T), 0.3);
}

// --fpfh-skip-horizontal: on a floor (z = 0) meeting a wall (x = 0), the floor's keypoints away
// from the wall have vertical normals and get no descriptor; the wall's all keep theirs. Oracle:
// the geometry (floor points have n = +-z, wall points n = +-x), not the code's own count.
TEST(Extract, FpfhSkipHorizontalDropsTheFloorAndKeepsTheWall) {
  Cloud room;
  for (int i = 0; i <= 100; ++i) {
    for (int j = 0; j <= 100; ++j) {
      room.emplace_back(0.1f * i, 0.1f * j - 5.0f, 0.0f);  // floor, 10 m x 10 m
      if (i <= 40) room.emplace_back(0.0f, 0.1f * j - 5.0f, 0.1f * i);  // wall, 4 m high
    }
  }
  PipelineFpfhParams p;
  p.voxel = 0.5;
  const auto away_floor = [](const Features& f) {  // floor keypoints 1.5 m from the wall
    int n = 0;
    for (const auto& q : f.points) n += q.z() < 0.3 && q.x() > 1.5;
    return n;
  };
  const auto wall = [](const Features& f) {
    int n = 0;
    for (const auto& q : f.points) n += q.x() < 0.3 && q.z() > 1.0;
    return n;
  };
  const Features all = features_fpfh(room, p);
  p.skip_horizontal_deg = 45;
  const Features kept = features_fpfh(room, p);
  EXPECT_GT(away_floor(all), 100);  // 20 x 17 voxels of floor there
  EXPECT_EQ(away_floor(kept), 0);
  EXPECT_GT(wall(all), 80);
  EXPECT_EQ(wall(kept), wall(all));
  EXPECT_EQ(kept.counts.at("horizontal_skipped") + kept.points.size(), all.points.size());
  for (double bad : {-1.0, 90.5, std::nan("")}) {
    p.skip_horizontal_deg = bad;
    EXPECT_THROW(features_fpfh(room, p), std::invalid_argument) << bad;
  }
}

// --max-matches keeps whole source keypoints, drawn by the seed, within the cap.
TEST(Extract, MatchCapKeepsWholeKeypointsAndFollowsTheSeed) {
  std::mt19937_64 rng(7);
  const Cloud source = drawn_street(rng);
  const Cloud target = moved(source, Rigid<3>::Identity(), rng, 0.01);
  ExtractParams p;
  p.matching = parse_matching("knn:3");
  p.max_hamming = 1000;  // every source keypoint gets exactly 3 matches
  const Features fs = extract_features(source, p), ft = extract_features(target, p);
  ASSERT_GE(ft.descriptors.size(), 3);
  const auto rows = [&](std::size_t cap, std::uint64_t seed) {
    ExtractParams q = p;
    q.max_matches = cap;
    q.seed = seed;
    const Dump d = match_features(fs, ft, std::nullopt, q);
    return std::get<LabeledSet<3>>(d.set).corr.source;
  };
  const auto all = rows(0, 1);
  ASSERT_EQ(all.cols(), 3 * fs.descriptors.size());
  const auto a = rows(31, 1), b = rows(31, 1), c = rows(31, 2);
  EXPECT_EQ(a.cols(), 30);  // 10 whole keypoints of 3 matches; an 11th would pass 31
  EXPECT_TRUE(a.isApprox(b));
  EXPECT_FALSE(a.isApprox(c));
  for (Eigen::Index k = 0; k < a.cols(); k += 3) {  // each keypoint's 3 matches stay together
    EXPECT_TRUE(a.col(k).isApprox(a.col(k + 1)) && a.col(k).isApprox(a.col(k + 2))) << k;
  }
}

TEST(CloudIo, MalformedAndEmptyCloudsAreNamedErrors) {
  const fs::path dir = fs::temp_directory_path() / "vb_clouds";
  fs::create_directories(dir);
  auto expect_error = [](const fs::path& p, const std::string& needle) {
    try {
      read_cloud(p.string());
      FAIL() << p;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(p.filename().string()), std::string::npos);
    }
  };
  std::ofstream(dir / "empty.bin", std::ios::binary).flush();
  expect_error(dir / "empty.bin", "no points");
  {
    std::ofstream out(dir / "ragged.bin", std::ios::binary);
    const float v[5] = {1, 2, 3, 4, 5};
    out.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  expect_error(dir / "ragged.bin", "20 bytes is not a whole number");
  {
    std::ofstream out(dir / "nan.bin", std::ios::binary);
    const float v[8] = {1, 2, 3, 0, 1, std::nanf(""), 3, 0};
    out.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  expect_error(dir / "nan.bin", "point 1 is not finite");
  std::ofstream(dir / "bad.ply") << "this is not a ply file\n";
  expect_error(dir / "bad.ply", "not a PLY header");
  // The files that crashed, hung or over-allocated inside PCL's readers (issue #15), refused by our
  // own header check first.
  std::ofstream(dir / "zero.pcd").flush();
  expect_error(dir / "zero.pcd", "empty file");
  std::ofstream(dir / "one.pcd") << "#";
  expect_error(dir / "one.pcd", "not a PCD header");
  std::ofstream(dir / "hello.pcd") << "hello";
  expect_error(dir / "hello.pcd", "not a PCD header");
  const std::string pcd_head =
      "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1000000000\n"
      "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1000000000\nDATA binary\n";
  std::ofstream(dir / "huge.pcd") << pcd_head << "0123456789AB";
  expect_error(dir / "huge.pcd", "promises 1000000000 points");
  std::ofstream(dir / "noz.pcd")
      << "VERSION .7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\nHEIGHT 1\n"
         "POINTS 1\nDATA ascii\n1 2\n";
  expect_error(dir / "noz.pcd", "no 'z'");
  std::ofstream(dir / "negative.ply")
      << "ply\nformat binary_little_endian 1.0\nelement vertex -42\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n";
  expect_error(dir / "negative.ply", "count = '-42'");
  std::ofstream(dir / "faces.ply")
      << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  expect_error(dir / "faces.ply", "element face");
  std::ofstream(dir / "noxyz.ply")
      << "ply\nformat ascii 1.0\nelement vertex 2\nproperty float a\nproperty float b\n"
         "end_header\n1 2\n3 4\n";
  expect_error(dir / "noxyz.ply", "lacks x, y or z");
  std::ofstream(dir / "huge.ply")
      << "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n0123";
  expect_error(dir / "huge.ply", "promises 1000000000 vertices");
  // Well-formed files still read, with the points they hold (the oracle: what was written).
  std::ofstream(dir / "ok.pcd")
      << "# a comment\nVERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
         "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n1 2 3\n4 5 6\n";
  const Cloud pcd = read_cloud((dir / "ok.pcd").string());
  ASSERT_EQ(pcd.size(), 2u);
  EXPECT_EQ(pcd[1], Eigen::Vector3f(4, 5, 6));
  {
    std::ofstream out(dir / "ok.ply", std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\ncomment test\nelement vertex 2\n"
           "property float x\nproperty float y\nproperty float z\nproperty float intensity\n"
           "end_header\n";
    const float v[8] = {1, 2, 3, 9, -4, 5.5f, 6, 9};
    out.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  const Cloud ply = read_cloud((dir / "ok.ply").string());
  ASSERT_EQ(ply.size(), 2u);
  EXPECT_EQ(ply[1], Eigen::Vector3f(-4, 5.5f, 6));
  std::ofstream(dir / "cloud.xyz") << "1 2 3\n";
  expect_error(dir / "cloud.xyz", "unknown point cloud extension");
  expect_error(dir / "missing.pcd", "no such file");
  std::ofstream(dir / "T.txt") << "1 0 0 0 0 1 0 0 0 0 2 0\n";  // scaled, not rigid
  EXPECT_THROW(read_transform((dir / "T.txt").string()), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace verifybench

namespace verifybench {
namespace {

TEST(Extract, RealKittiPairsAcceptThePositiveAndRejectTheNegative) {
  const fs::path k00 = fs::path(VERIFYBENCH_SHARED_DATA) / "kitti/00_scans_94_95_198_199";
  if (!fs::exists(k00)) GTEST_SKIP() << k00 << " not found (real data lives beside the checkout)";
  register_builtin_solvers();
  SolverParams sp;  // the paper's setting: eps 1 m, accept at 5 inliers in 3D, 10 in 2D
  sp.eps = 1.0;
  sp.inlier_threshold = 1.0;
  for (const char* pipeline : {"3d", "2d"}) {
    ExtractParams p;
    p.pipeline = pipeline;
    const Dump pos = extract((k00 / "000095.bin").string(), (k00 / "000094.bin").string(),
                             (k00 / "T_94_95.txt").string(), p);
    const Dump neg = extract((k00 / "000198.bin").string(), (k00 / "000094.bin").string(),
                             (k00 / "T_94_198.txt").string(), p);
    std::visit(
        [&](const auto& s) {
          const auto r = SolverRegistry::create("clique")->solve(s.corr, sp);
          EXPECT_TRUE(r.accepted) << pipeline;
          EXPECT_LT(rotation_error_deg(r.T_target_source, *s.truth.T_target_source), 3.0);
          EXPECT_LT(translation_error(r.T_target_source, *s.truth.T_target_source), 0.5);
        },
        pos.set);
    std::visit(
        [&](const auto& s) {
          // 58 m apart, ~4% overlap: no labelled inlier, and the verifier must say no.
          EXPECT_EQ(std::count(s.truth.labels.begin(), s.truth.labels.end(), 1), 0) << pipeline;
          EXPECT_FALSE(SolverRegistry::create("clique")->solve(s.corr, sp).accepted) << pipeline;
        },
        neg.set);
  }
}

// `run`'s dense check on dumps that keep their clouds (extract --keep-clouds), against motions the
// test draws: a scene of walls and boxes seen from two frames; one correspondence set follows the
// true motion, the other a rigid alias (every match consistent with a motion 9 m and 70 deg off,
// the failure of repetitive structure). The calibrated rule accepts both; the kept clouds refute
// the alias and keep the truth, and without clouds, with --dense-overlap 0 or under the count
// rule (the paper's: no check) the alias stands.
TEST(KeptClouds, RunsDenseCheckRejectsARigidAliasAndKeepsTheTruth) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> world;  // in the target frame: two walls and 40 boxes, 0.2 m apart
  for (double a = -20; a <= 20; a += 0.2) {
    for (double z = 0; z <= 5; z += 0.2) {
      world.emplace_back(a, 20.0, z);
      world.emplace_back(-20.0, a, z);
    }
  }
  for (int b = 0; b < 40; ++b) {
    const double cx = -18 + 36 * u(rng), cy = -18 + 36 * u(rng), h = 1 + 3 * u(rng);
    const double w = 0.6 + 1.4 * u(rng);
    for (double d = 0; d <= w; d += 0.2) {
      for (double z = 0; z <= h; z += 0.2) {
        world.emplace_back(cx + d, cy, z);
        world.emplace_back(cx, cy + d, z);
        world.emplace_back(cx + d, cy + w, z);
      }
    }
  }
  Rigid<3> T_true = Rigid<3>::Identity();
  T_true.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_true.translation() = Eigen::Vector3d(2.0, -3.0, 0.0);
  Rigid<3> T_alias = T_true;
  T_alias.linear() = Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                     T_true.linear();
  T_alias.translation() += Eigen::Vector3d(9.0, 0.0, 0.0);
  DumpClouds clouds;
  for (const auto& p : world) {
    clouds.target.push_back(p.cast<float>());
    clouds.source.push_back((T_true.inverse() * p).cast<float>());
  }
  // 60 matches of source points under `T` (noise 2 cm) among 240 uniform outliers.
  auto set_for = [&](const Rigid<3>& T, bool is_truth) {
    LabeledSet<3> s;
    const int inliers = 60, n = 300;
    s.corr.source.resize(3, n);
    s.corr.target.resize(3, n);
    std::normal_distribution<double> noise(0.0, 0.02);
    for (int i = 0; i < n; ++i) {
      const auto& m = clouds.source[static_cast<std::size_t>(rng() % clouds.source.size())];
      s.corr.source.col(i) = m.cast<double>();
      if (i < inliers) {
        s.corr.target.col(i) =
            T * m.cast<double>() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      } else {
        s.corr.target.col(i) = Eigen::Vector3d(-20 + 40 * u(rng), -20 + 40 * u(rng), 5 * u(rng));
      }
      s.truth.labels.push_back(is_truth && i < inliers ? 1 : 0);
    }
    s.truth.T_target_source = T_true;
    return s;
  };
  const fs::path root = fs::temp_directory_path() / "vb_kept_clouds";
  fs::remove_all(root);
  fs::create_directories(root);
  auto dump_of = [&](const Rigid<3>& T, bool is_truth, const std::string& name, bool keep) {
    Dump d;
    d.set = set_for(T, is_truth);
    if (keep) d.clouds = clouds;
    write_dump((root / name).string(), d);
    return (root / name).string();
  };
  const std::string truth = dump_of(T_true, true, "truth", true);
  const std::string alias = dump_of(T_alias, false, "alias", true);
  const std::string bare = dump_of(T_alias, false, "alias_bare", false);
  auto run = [&](const std::string& dump, const std::string& extra, const std::string& tag) {
    const fs::path out = root / (tag + ".json");
    const auto r = test::run_cli("run --dump " + dump + " --solvers clique,ransac --eps 0.2 " +
                                 "--time-limit 10 --quiet " + extra + " --out " + out.string());
    EXPECT_EQ(r.code, 0) << r.output;
    std::ifstream in(out);
    return nlohmann::json::parse(in);
  };
  const auto t = run(truth, "", "truth");
  EXPECT_EQ(t["parameters"]["run"]["dense_check"]["min_overlap"].get<double>(),
            kDefaultScanOverlap);
  // The clouds decide: the runner-up test is off unless asked (the report holds the level in force).
  EXPECT_EQ(t["parameters"]["runner_up_alpha"].get<double>(), 0.0);
  for (const auto& row : t["results"]) {
    EXPECT_TRUE(row["accepted"].get<bool>()) << row.dump();
    ASSERT_TRUE(row["dense_check"].is_object()) << row.dump();
    EXPECT_GT(row["dense_check"]["overlap"].get<double>(), 0.9) << row.dump();
    EXPECT_EQ(row["decision"], "TP");
  }
  const auto a = run(alias, "", "alias");
  for (const auto& row : a["results"]) {
    EXPECT_FALSE(row["accepted"].get<bool>()) << row.dump();
    EXPECT_LT(row["p_value"].get<double>(), 1e-6) << row.dump();  // the rule alone accepts it
    ASSERT_TRUE(row["dense_check"].is_object()) << row.dump();
    EXPECT_LT(row["dense_check"]["overlap"].get<double>(), kDefaultScanOverlap) << row.dump();
    EXPECT_NE(row["message"].get<std::string>().find("dense check"), std::string::npos);
    EXPECT_EQ(row["decision"], "TN");
    std::printf("alias, %s: overlap %.3f after ICP\n", row["solver"].get<std::string>().c_str(),
                row["dense_check"]["overlap"].get<double>());
  }
  for (const auto& [dump, extra, tag] :
       {std::tuple{bare, std::string(), "bare"}, std::tuple{alias, std::string("--dense-overlap 0"), "off"},
        std::tuple{alias, std::string("--accept count"), "count"}}) {
    const auto r = run(dump, extra, tag);
    EXPECT_TRUE(r["parameters"]["run"]["dense_check"].is_null() ||
                r["parameters"]["run"]["dense_check"]["min_overlap"].get<double>() == 0.0)
        << tag;
    // No dense check: the runner-up test runs at alpha under the calibrated rule (one alias among
    // uniform outliers has no rival, so it stands), not at all under count.
    const double level = tag == std::string("count") ? 0.0 : 0.001;
    EXPECT_EQ(r["parameters"]["runner_up_alpha"].get<double>(), level) << tag;
    for (const auto& row : r["results"]) {
      EXPECT_TRUE(row["accepted"].get<bool>()) << tag << " " << row.dump();
      EXPECT_EQ(row["runner_up"].is_null(), level == 0.0) << tag << " " << row.dump();
      EXPECT_TRUE(row["dense_check"].is_null()) << tag;
      EXPECT_EQ(row["decision"], "FP") << tag;
    }
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace verifybench
