#include "loop/retrieval.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace verifybench {

void RetrievalParams::validate() const {
  auto check = [](const char* name, int v, int lo) {
    if (v < lo) {
      throw std::invalid_argument(std::string("retrieval: ") + name + " must be >= " +
                                  std::to_string(lo) + ", got " + std::to_string(v));
    }
  };
  check("candidates", candidates, 1);
  check("min_votes", min_votes, 1);
  check("max_hamming", max_hamming, 0);
  check("min_map_gap", min_map_gap, 1);
}

std::vector<Candidate> retrieve_candidates(const std::vector<Features>& maps,
                                           const RetrievalParams& params) {
  params.validate();
  std::vector<Candidate> out;
  int bits = -1;
  for (const auto& f : maps) {
    if (f.descriptors.size() == 0) continue;
    if (bits >= 0 && f.descriptors.bits != bits) {
      throw std::invalid_argument("retrieval: descriptors of " + std::to_string(bits) + " and " +
                                  std::to_string(f.descriptors.bits) + " bits");
    }
    bits = f.descriptors.bits;
  }
  if (bits < 0) return out;
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
    std::vector<int> votes(maps.size(), 0);
    const BinaryDescriptors& d = maps[q].descriptors;
    for (int k = 0; k < d.size(); ++k) {
      const BinaryMatch m = tree.nearest(d.row(k), params.max_hamming, params.exact);
      if (m.index >= 0) ++votes[owner[m.index]];
    }
    std::vector<int> order;
    for (int j = 0; j < static_cast<int>(maps.size()); ++j) {
      if (votes[j] >= params.min_votes) order.push_back(j);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return votes[a] > votes[b]; });
    if (static_cast<int>(order.size()) > params.candidates) order.resize(params.candidates);
    for (int j : order) out.push_back({q, j, votes[j]});
  }
  return out;
}

}  // namespace verifybench
