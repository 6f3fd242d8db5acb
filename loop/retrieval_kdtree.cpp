// Retrieval by real-valued descriptors (FPFH): each descriptor of map q votes for the map of its
// nearest descriptor among maps 0 .. q - min_map_gap, in feature space (Euclidean, exact k-d tree
// of frontend/matching.hpp), when within max_feature_distance. The database is rebuilt for each
// query, so the votes are exactly those of a brute-force search over the database.
#include <stdexcept>

#include "frontend/matching.hpp"
#include "loop/retrieval.hpp"

namespace verifybench {

std::vector<std::vector<int>> kdtree_votes(const std::vector<Features>& maps,
                                           const RetrievalParams& params) {
  std::vector<std::vector<int>> votes(maps.size(), std::vector<int>(maps.size(), 0));
  RealDescriptors database;
  std::vector<int> owner;  // database row -> map
  int inserted = 0;
  for (int q = 0; q < static_cast<int>(maps.size()); ++q) {
    if (maps[q].descriptors.size() > 0) {
      throw std::invalid_argument("retrieval kdtree: the maps have binary descriptors (use hbst)");
    }
    for (; inserted <= q - params.min_map_gap; ++inserted) {
      const RealDescriptors& d = maps[inserted].real;
      if (d.size() == 0) continue;
      if (database.dims != 0 && d.dims != database.dims) {
        throw std::invalid_argument("retrieval: descriptors of " + std::to_string(database.dims) +
                                    " and " + std::to_string(d.dims) + " dimensions");
      }
      database.dims = d.dims;
      database.data.insert(database.data.end(), d.data.begin(), d.data.end());
      owner.insert(owner.end(), d.size(), inserted);
    }
    if (database.size() == 0 || maps[q].real.size() == 0) continue;
    MatchingPolicy nearest;
    nearest.kind = MatchingPolicy::Kind::nearest;
    for (const FeatureMatch& m :
         match_real(maps[q].real, database, nearest, params.max_feature_distance)) {
      ++votes[q][owner[m.target]];
    }
  }
  return votes;
}

}  // namespace verifybench
