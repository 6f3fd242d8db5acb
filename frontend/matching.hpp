#pragma once
// Matching policies between two scans' descriptors (binary: Hamming distance; FPFH: Euclidean
// distance in the 33-bin feature space). Which matches a front end keeps decides how many true
// ones reach the verifier: a single nearest neighbour can leave a real loop with 3 true matches of
// 117 where every match within 50 bits (the paper's HBST query) keeps 11 of 3664.
#include <string>
#include <vector>

#include "frontend/features.hpp"

namespace verifybench {

struct MatchingPolicy {
  enum class Kind { nearest, mutual, knn, radius, ratio };
  Kind kind = Kind::nearest;
  int k = 1;  ///< knn: neighbours per source descriptor
  double ratio = 0.9;  ///< ratio: keep the nearest when d1 < ratio * d2
  /// "nearest", "mutual", "knn:K", "radius", "ratio:R"
  std::string name() const;
};

/// Parses --matching; throws std::invalid_argument naming the text and the choices.
MatchingPolicy parse_matching(const std::string& text);

struct FeatureMatch {
  int source = 0, target = 0;
  double distance = 0;  ///< Hamming bits or feature-space Euclidean distance
};

/// Every policy keeps only matches within `max_distance`:
///   nearest  the nearest target descriptor of each source one (ties: lowest index)
///   mutual   a nearest match whose target's nearest source descriptor is that source
///   knn:K    the K nearest target descriptors of each source one
///   radius   every target descriptor within max_distance
///   ratio:R  the nearest, when closer than R times the second nearest within max_distance
///            (Lowe's ratio test, IJCV 2004: a descriptor that many others resemble, as flat
///            ground's FPFH or a corridor's, matches nowhere in particular)
/// Sorted by source, then distance, then target. Exhaustive (the reference for HBST).
std::vector<FeatureMatch> match_binary(const BinaryDescriptors& source,
                                       const BinaryDescriptors& target,
                                       const MatchingPolicy& policy, int max_distance);
/// The same for FPFH through exact k-d tree searches (PCL's KdTreeFLANN).
std::vector<FeatureMatch> match_real(const RealDescriptors& source, const RealDescriptors& target,
                                     const MatchingPolicy& policy, double max_distance);

}  // namespace verifybench
