#pragma once
// Candidate retrieval (the paper's Sec. III-B): which older maps each new map is verified against.
// Maps closer than min_map_gap in sequence are never compared: when map i asks, the database holds
// maps 0 .. i - min_map_gap. Each kind of retriever is one file behind the registry below:
//   hbst    binary descriptors (3d, 2d): each descriptor of the query map votes for the map of its
//           nearest database descriptor within max_hamming bits, through one HBST (one leaf, the
//           paper's approximate mode; --exact-retrieval backtracks to the true nearest);
//   kdtree  real descriptors (fpfh): each descriptor votes for the map of its nearest database
//           descriptor in feature space within max_feature_distance (exact k-d tree);
//   all     every map in the database is a candidate (small sequences; votes = 0).
// The `candidates` maps with the most votes (at least min_votes; ties: the older map) go to
// verification; `auto` takes hbst for binary descriptors and kdtree for real ones.
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/param_rows.hpp"
#include "frontend/features.hpp"
#include "frontend/hbst.hpp"

namespace verifybench {

struct RetrievalParams {
  std::string method = "auto";  ///< a registered retriever, or auto
  int candidates = 2;    ///< maps verified per query
  int min_votes = 5;     ///< fewer votes: not a candidate (not used by `all`)
  int max_hamming = 50;  ///< bits (hbst)
  double max_feature_distance = std::numeric_limits<double>::infinity();  ///< kdtree
  int min_map_gap = 3;   ///< maps fewer than this apart are not compared
  bool exact = false;    ///< hbst with backtracking (the true nearest) instead of one leaf
  HbstParams hbst;
  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// Retrieval's settings a user sets (`loop --retrieval`, `--candidates`, `--min-votes`,
/// `--min-map-gap`, `--exact-retrieval`; --max-hamming and --max-feature-distance are the front
/// end's), as rows.
const std::vector<ParamRow<RetrievalParams>>& retrieval_param_rows();

struct Candidate {
  int query = 0;  ///< the newer map (source of the verification)
  int match = 0;  ///< the older map (target)
  int votes = 0;
};

/// Votes of query map q for every map (0 for maps outside its database).
using VoteFunction =
    std::function<std::vector<int>(const std::vector<Features>& maps, const RetrievalParams&)>;

struct RetrieverInfo {
  std::string name;
  std::string help;
  /// Each map's votes for every map: votes[q][j], j in q's database (0 elsewhere).
  std::function<std::vector<std::vector<int>>(const std::vector<Features>& maps,
                                              const RetrievalParams& params)>
      votes;
  bool uses_votes = true;  ///< false: every database map is a candidate (min_votes ignored)
};
std::vector<RetrieverInfo> list_retrievers();
/// The retriever params.method names (auto resolved by the maps' descriptors).
std::string resolve_retriever(const std::vector<Features>& maps, const RetrievalParams& params);

/// Candidates of every query map, by query then votes (descending). Throws std::invalid_argument
/// when the maps' descriptors differ in kind or length, or the retriever cannot read them.
std::vector<Candidate> retrieve_candidates(const std::vector<Features>& maps,
                                           const RetrievalParams& params);

// The kinds (one file each).
std::vector<std::vector<int>> hbst_votes(const std::vector<Features>& maps,
                                         const RetrievalParams& params);
std::vector<std::vector<int>> kdtree_votes(const std::vector<Features>& maps,
                                           const RetrievalParams& params);

}  // namespace verifybench
