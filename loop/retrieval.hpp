#pragma once
// Candidate retrieval (the paper's Sec. III-B): one HBST database over the binary descriptors of
// every local map; each descriptor of a query map votes for the map of its nearest database
// descriptor within max_hamming bits (one leaf, the paper's approximate mode). Maps closer than
// min_map_gap in sequence are never compared: the database holds maps 0 .. i - min_map_gap when
// map i asks. The `candidates` maps with the most votes (at least min_votes; ties: the older map)
// go to verification.
#include <vector>

#include "frontend/features.hpp"
#include "frontend/hbst.hpp"

namespace verifybench {

struct RetrievalParams {
  int candidates = 2;    ///< maps verified per query
  int min_votes = 5;     ///< fewer votes: not a candidate
  int max_hamming = 50;  ///< bits
  int min_map_gap = 3;   ///< maps fewer than this apart are not compared
  bool exact = false;    ///< HBST with backtracking (the true nearest) instead of one leaf
  HbstParams hbst;
  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

struct Candidate {
  int query = 0;  ///< the newer map (source of the verification)
  int match = 0;  ///< the older map (target)
  int votes = 0;
};

/// Candidates of every query map, by query then votes (descending). Throws std::invalid_argument
/// when the maps' descriptors have different bit lengths.
std::vector<Candidate> retrieve_candidates(const std::vector<Features>& maps,
                                           const RetrievalParams& params);

}  // namespace verifybench
