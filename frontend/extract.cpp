#include "frontend/extract.hpp"

#include <cmath>
#include <mutex>
#include <numeric>
#include <random>
#include <stdexcept>

#include "core/random.hpp"
#include "core/registry.hpp"
#include "core/timer.hpp"

namespace verifybench {

using json = nlohmann::json;

Rigid<2> planar(const Rigid<3>& T) {
  Rigid<2> out = Rigid<2>::Identity();
  const double yaw = std::atan2(T.linear()(1, 0), T.linear()(0, 0));
  out.linear() = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  out.translation() = T.translation().head<2>();
  return out;
}

namespace {

template <int Dim>
LabeledSet<Dim> assemble(const Features& s, const Features& t, const std::vector<FeatureMatch>& m,
                         const std::optional<Rigid<Dim>>& T, double label_threshold) {
  LabeledSet<Dim> set;
  const auto n = static_cast<Eigen::Index>(m.size());
  set.corr.source.resize(Dim, n);
  set.corr.target.resize(Dim, n);
  set.corr.score.resize(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    set.corr.source.col(i) = s.points[static_cast<std::size_t>(m[k].source)].head<Dim>();
    set.corr.target.col(i) = t.points[static_cast<std::size_t>(m[k].target)].head<Dim>();
    set.corr.score[k] = -m[k].distance;  // higher = better
  }
  if (T) {
    set.truth.T_target_source = *T;
    set.truth.labels.resize(m.size());
    for (Eigen::Index i = 0; i < n; ++i) {
      set.truth.labels[static_cast<std::size_t>(i)] =
          (*T * set.corr.source.col(i) - set.corr.target.col(i)).norm() < label_threshold;
    }
  }
  return set;
}

/// Keeps whole source keypoints, drawn in a seeded random order, while the matches fit the cap;
/// the kept matches stay in their original order.
std::vector<FeatureMatch> capped(std::vector<FeatureMatch> matches, std::size_t sources,
                                 std::size_t cap, std::uint64_t seed) {
  std::vector<std::size_t> per_source(sources, 0);
  for (const auto& m : matches) ++per_source[static_cast<std::size_t>(m.source)];
  std::vector<int> order(sources);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(derive_seed(seed, {0x434150u}));
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<char> keep(sources, 0);
  std::size_t total = 0;
  for (int s : order) {
    const std::size_t k = per_source[static_cast<std::size_t>(s)];
    if (k == 0 || total + k > cap) continue;
    keep[static_cast<std::size_t>(s)] = 1;
    total += k;
  }
  std::vector<FeatureMatch> out;
  out.reserve(total);
  for (const auto& m : matches) {
    if (keep[static_cast<std::size_t>(m.source)]) out.push_back(m);
  }
  return out;
}

json provenance_3d(const ExtractParams& params) {
  const auto& p3 = params.p3;
  return {{"name", "3d: voxel grid, ISS, normals, SHOT, B-SHOT"},
          {"voxel", p3.voxel},
          {"iss_salient_radius", p3.salient_radius},
          {"iss_non_max_radius", p3.non_max_radius},
          {"iss_gamma21", p3.gamma21},
          {"iss_gamma32", p3.gamma32},
          {"iss_min_neighbors", p3.min_neighbors},
          {"normal_radius", p3.normal_radius},
          {"shot_radius", p3.shot_radius}};
}

json provenance_fpfh(const ExtractParams& params) {
  const auto& pf = params.pf;
  return {{"name", "fpfh: voxel grid (keypoints = voxel centroids), normals, FPFH"},
          {"voxel", pf.voxel},
          {"normal_radius", pf.normal_radius > 0 ? pf.normal_radius : 2 * pf.voxel},
          {"fpfh_radius", pf.fpfh_radius > 0 ? pf.fpfh_radius : 5 * pf.voxel},
          {"skip_horizontal_deg", pf.skip_horizontal_deg}};
}

json provenance_2d(const ExtractParams& params) {
  const auto& p2 = params.p2;
  return {{"name", "2d: bird's-eye-view density image, ORB"},
          {"cell", p2.bev.cell},
          {"min_fraction", p2.bev.min_fraction},
          {"range", p2.bev.range},
          {"orb_features", p2.orb_features}};
}

const Registry<PipelineInfo>& pipelines() {
  static Registry<PipelineInfo> registry("pipeline", Registry<PipelineInfo>::Order::as_added);
  static std::once_flag once;
  std::call_once(once, [] {
    registry.add({"3d", "ISS keypoints + B-SHOT (PCL)",
                  [](const Cloud& c, const ExtractParams& p) { return features_3d(c, p.p3); },
                  provenance_3d});
    registry.add({"2d", "bird's-eye-view density image + ORB (OpenCV)",
                  [](const Cloud& c, const ExtractParams& p) { return features_2d(c, p.p2); },
                  provenance_2d});
    registry.add({"fpfh", "voxel centroids + FPFH (PCL), matched in the 33-bin feature space",
                  [](const Cloud& c, const ExtractParams& p) { return features_fpfh(c, p.pf); },
                  provenance_fpfh});
  });
  return registry;
}

}  // namespace

std::vector<PipelineInfo> list_pipelines() { return pipelines().list(); }

Features extract_features(const Cloud& cloud, const ExtractParams& params) {
  return pipelines().get(params.pipeline).features(cloud, params);
}

Dump match_features(const Features& source, const Features& target,
                    const std::optional<Rigid<3>>& T_target_source, const ExtractParams& params) {
  if (params.max_hamming < 0 || !(params.label_threshold > 0.0)) {
    throw std::invalid_argument("max_hamming must be >= 0 and label_threshold > 0");
  }
  if (params.matching.kind == MatchingPolicy::Kind::radius && source.real.dims > 0 &&
      !std::isfinite(params.max_feature_distance)) {
    throw std::invalid_argument("radius matching of FPFH needs a finite max_feature_distance");
  }
  if (source.descriptors.bits != target.descriptors.bits) {
    throw std::invalid_argument("source and target descriptors differ in length");
  }
  const bool real = source.real.dims > 0;
  if (real != (target.real.dims > 0)) {
    throw std::invalid_argument("source and target descriptors are of different kinds");
  }
  json matcher = {{"policy", params.matching.name()}};
  std::vector<FeatureMatch> matches;
  double build_ms = 0;
  StopWatch query_clock;
  if (real) {
    matches = match_real(source.real, target.real, params.matching, params.max_feature_distance);
    matcher["name"] = "k-d tree in FPFH space (exact)";
    matcher["max_feature_distance"] = std::isfinite(params.max_feature_distance)
                                          ? json(params.max_feature_distance)
                                          : json(nullptr);
    matcher["score"] = "minus the feature-space distance";
  } else if (params.matching.kind == MatchingPolicy::Kind::nearest) {
    // The paper's matcher: the nearest descriptor through an HBST (one leaf, or exact).
    StopWatch clock;
    HbstTree tree(std::max(1, target.descriptors.bits), params.hbst);
    tree.insert(target.descriptors);
    build_ms = clock.ms();
    query_clock = StopWatch();
    for (int i = 0; i < source.descriptors.size(); ++i) {
      const BinaryMatch m =
          tree.nearest(source.descriptors.row(i), params.max_hamming, params.exact_matching);
      if (m.index >= 0) matches.push_back({i, m.index, static_cast<double>(m.distance)});
    }
    matcher["name"] =
        params.exact_matching ? "HBST, exact (backtracking)" : "HBST, one leaf (approximate)";
    matcher["max_leaf_size"] = params.hbst.max_leaf_size;
    matcher["tree_depth"] = tree.depth();
  } else {
    matches =
        match_binary(source.descriptors, target.descriptors, params.matching, params.max_hamming);
    matcher["name"] = "exhaustive Hamming search";
  }
  if (!real) {
    matcher["max_hamming"] = params.max_hamming;
    matcher["score"] = "minus the Hamming distance [bits]";
  }
  const double query_ms = query_clock.ms();
  const std::size_t matched = matches.size();
  if (params.max_matches > 0 && matches.size() > params.max_matches) {
    matches = capped(std::move(matches), source.points.size(), params.max_matches, params.seed);
  }
  matcher["max_matches"] = params.max_matches;
  matcher["matches_before_cap"] = matched;
  matcher["seed"] = params.seed;

  Dump dump;
  if (source.dim == 3) {
    dump.set = assemble<3>(source, target, matches, T_target_source, params.label_threshold);
  } else {
    std::optional<Rigid<2>> T2;
    if (T_target_source) T2 = planar(*T_target_source);
    dump.set = assemble<2>(source, target, matches, T2, params.label_threshold);
  }
  if (T_target_source) dump.label_threshold = params.label_threshold;
  const json pipeline = pipelines().get(params.pipeline).provenance(params);
  dump.provenance = {
      {"tool", "verifybench extract"},
      {"pipeline", pipeline},
      {"matcher", matcher},
      {"counts",
       {{"source", source.counts}, {"target", target.counts}, {"matches", matches.size()}}},
      {"ms",
       {{"source", source.ms},
        {"target", target.ms},
        {"hbst_build", build_ms},
        {"match", query_ms}}}};
  return dump;
}

Dump extract(const std::string& source_cloud, const std::string& target_cloud,
             const std::optional<std::string>& transform_file, const ExtractParams& params) {
  std::optional<Rigid<3>> T;
  if (transform_file) T = read_transform(*transform_file);
  const Cloud src = read_cloud(source_cloud);
  const Cloud tgt = read_cloud(target_cloud);
  StopWatch clock;
  const Features fs = extract_features(src, params);
  const Features ft = extract_features(tgt, params);
  Dump dump = match_features(fs, ft, T, params);
  dump.provenance["inputs"] = {
      {"source", source_cloud},
      {"target", target_cloud},
      {"T_target_source", transform_file ? json(*transform_file) : json(nullptr)}};
  if (params.keep_clouds) {
    DumpClouds kept;
    kept.voxel = params.cloud_voxel;
    kept.source = params.cloud_voxel > 0.0 ? voxel_downsample(src, params.cloud_voxel) : src;
    kept.target = params.cloud_voxel > 0.0 ? voxel_downsample(tgt, params.cloud_voxel) : tgt;
    dump.clouds = std::move(kept);
  }
  dump.provenance["ms"]["total"] = clock.ms();
  return dump;
}

}  // namespace verifybench
