#pragma once
// `verifybench extract`: two scans (and optionally their ground-truth motion) in, a correspondence
// dump out. Features from the 3D or 2D pipeline on both scans, then every source descriptor is
// matched to its nearest target descriptor by Hamming distance through an HBST built
// incrementally over the target's descriptors; a match is kept within max_hamming bits. Labels,
// when the ground truth is given: 1 when ||T m - q|| < label_threshold.
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "datasets/dump_format.hpp"
#include "frontend/features.hpp"
#include "frontend/hbst.hpp"
#include "frontend/matching.hpp"

namespace verifybench {

struct ExtractParams {
  std::string pipeline = "3d";  ///< "3d" (ISS + B-SHOT), "2d" (BEV + ORB) or "fpfh"
  Pipeline3dParams p3;
  Pipeline2dParams p2;
  PipelineFpfhParams pf;
  MatchingPolicy matching;  ///< nearest (binary: through the HBST), mutual, knn:K, radius
  /// FPFH: keep matches within this feature-space distance (radius needs it finite)
  double max_feature_distance = std::numeric_limits<double>::infinity();
  /// Cap on the dump's rows (0 = none): source keypoints are drawn in a seeded random order and
  /// kept with all their matches while the total stays within the cap (k-NN dumps of big scans).
  std::size_t max_matches = 0;
  std::uint64_t seed = 1;       ///< the draw of the cap
  int max_hamming = 50;         ///< keep a match within this many bits
  bool exact_matching = false;  ///< HBST with backtracking (= brute force) instead of one leaf
  HbstParams hbst;
  double label_threshold = 1.0;  ///< [m]; the paper's eps in 3D
  /// extract(): keep both clouds in the dump (datasets/dump_clouds.hpp), thinned on a grid of
  /// cloud_voxel (0 = as read), for the dense check of `run` (acceptance/dense_check.hpp): on by
  /// default, so that a dump is decided by the default rule with everything it needs.
  bool keep_clouds = true;
  double cloud_voxel = 0.25;  ///< [m]
};

/// A front-end pipeline: one scan in, keypoints and binary descriptors out.
struct PipelineInfo {
  std::string name;  ///< "3d", "2d"
  std::string description;
  std::function<Features(const Cloud&, const ExtractParams&)> features;
  std::function<nlohmann::json(const ExtractParams&)> provenance;  ///< its parameters, for dumps
};
/// The pipelines, in a stable order.
std::vector<PipelineInfo> list_pipelines();

/// One scan's features, by pipeline; UnknownName for an unknown one.
Features extract_features(const Cloud& cloud, const ExtractParams& params);

/// The planar part of a motion: its yaw (rotation about z) and x-y translation, the frame of the
/// 2D pipeline's sets.
Rigid<2> planar(const Rigid<3>& T);

/// Source features matched into target features; T (3D, for the 2D pipeline reduced to its yaw
/// and x-y translation) labels them. Provenance: inputs are the caller's; this adds parameters,
/// counts and timings.
Dump match_features(const Features& source, const Features& target,
                    const std::optional<Rigid<3>>& T_target_source, const ExtractParams& params);

/// The whole command: reads the clouds and the optional transform file (`T_target_source`,
/// 12 or 16 numbers), records the input paths in the provenance.
Dump extract(const std::string& source_cloud, const std::string& target_cloud,
             const std::optional<std::string>& transform_file, const ExtractParams& params);

}  // namespace verifybench
