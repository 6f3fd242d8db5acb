// Retrieval by binary descriptors through one HBST (Schlegel and Grisetti, RA-L 2018), as the
// paper's Sec. III-B: the database grows map by map, so map q asks a tree that holds exactly the
// maps 0 .. q - min_map_gap.
#include <stdexcept>
#include <string>

#include "loop/retrieval.hpp"

namespace verifybench {

std::vector<std::vector<int>> hbst_votes(const std::vector<Features>& maps,
                                         const RetrievalParams& params) {
  std::vector<std::vector<int>> votes(maps.size(), std::vector<int>(maps.size(), 0));
  int bits = -1;
  for (const auto& f : maps) {
    if (f.real.dims > 0) {
      throw std::invalid_argument("retrieval hbst: the maps have real descriptors (use kdtree)");
    }
    if (f.descriptors.size() == 0) continue;
    if (bits >= 0 && f.descriptors.bits != bits) {
      throw std::invalid_argument("retrieval: descriptors of " + std::to_string(bits) + " and " +
                                  std::to_string(f.descriptors.bits) + " bits");
    }
    bits = f.descriptors.bits;
  }
  if (bits < 0) return votes;
  HbstTree tree(bits, params.hbst);
  std::vector<int> owner;  // database descriptor id -> map
  int inserted = 0;
  for (int q = 0; q < static_cast<int>(maps.size()); ++q) {
    for (; inserted <= q - params.min_map_gap; ++inserted) {
      const BinaryDescriptors& d = maps[inserted].descriptors;
      if (d.size() == 0) continue;
      tree.insert(d);
      owner.insert(owner.end(), d.size(), inserted);
    }
    if (tree.size() == 0 || maps[q].descriptors.size() == 0) continue;
    const BinaryDescriptors& d = maps[q].descriptors;
    for (int k = 0; k < d.size(); ++k) {
      const BinaryMatch m = tree.nearest(d.row(k), params.max_hamming, params.exact);
      if (m.index >= 0) ++votes[q][owner[m.index]];
    }
  }
  return votes;
}

}  // namespace verifybench
