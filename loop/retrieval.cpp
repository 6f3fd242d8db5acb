#include "loop/retrieval.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/registry.hpp"

namespace verifybench {

namespace {

Registry<RetrieverInfo>& retrievers() {
  static Registry<RetrieverInfo>* registry = [] {
    auto* r = new Registry<RetrieverInfo>("retriever", Registry<RetrieverInfo>::Order::as_added);
    r->add({"hbst", "binary descriptors: votes by the nearest within --max-hamming (HBST)",
            hbst_votes, true});
    r->add({"kdtree", "real descriptors (fpfh): votes by the nearest in feature space (k-d tree)",
            kdtree_votes, true});
    r->add({"all", "every older map beyond --min-map-gap (small sequences)",
            [](const std::vector<Features>& maps, const RetrievalParams&) {
              return std::vector<std::vector<int>>(maps.size(),
                                                   std::vector<int>(maps.size(), 0));
            },
            false});
    return r;
  }();
  return *registry;
}

}  // namespace

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
  if (!(max_feature_distance >= 0.0)) {
    throw std::invalid_argument("retrieval: max_feature_distance must be >= 0, got " +
                                std::to_string(max_feature_distance));
  }
  if (method != "auto" && !retrievers().contains(method)) {
    throw std::invalid_argument("retrieval: unknown retriever '" + method +
                                "' (known: auto, " + retrievers().known() + ")");
  }
}

std::vector<RetrieverInfo> list_retrievers() { return retrievers().list(); }

std::string resolve_retriever(const std::vector<Features>& maps, const RetrievalParams& params) {
  if (params.method != "auto") return params.method;
  for (const Features& f : maps) {
    if (f.real.dims > 0) return "kdtree";
  }
  return "hbst";
}

std::vector<Candidate> retrieve_candidates(const std::vector<Features>& maps,
                                           const RetrievalParams& params) {
  params.validate();
  const RetrieverInfo& info = retrievers().get(resolve_retriever(maps, params));
  const auto votes = info.votes(maps, params);
  std::vector<Candidate> out;
  const int n = static_cast<int>(maps.size());
  for (int q = 0; q < n; ++q) {
    std::vector<int> order;
    for (int j = 0; j + params.min_map_gap <= q; ++j) {
      if (!info.uses_votes || votes[q][j] >= params.min_votes) order.push_back(j);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return votes[q][a] > votes[q][b]; });
    if (info.uses_votes && static_cast<int>(order.size()) > params.candidates) {
      order.resize(params.candidates);
    }
    for (int j : order) out.push_back({q, j, votes[q][j]});
  }
  return out;
}

const std::vector<ParamRow<RetrievalParams>>& retrieval_param_rows() {
  using P = RetrievalParams;
  static const std::vector<ParamRow<P>> rows = [] {
    std::vector<ParamRow<P>> r;
    r.push_back(field_row(&P::min_map_gap, "min-map-gap", "min_map_gap", "K",
                          "maps fewer than K apart are not compared", 1, 1 << 20,
                          "an integer >= 1"));
    r.push_back(field_row(&P::candidates, "candidates", "candidates", "K",
                          "maps verified per query (most votes)", 1, 1 << 20, "an integer >= 1"));
    r.push_back(field_row(&P::min_votes, "min-votes", "min_votes", "K",
                          "fewer votes: not a candidate", 1, 1 << 30, "an integer >= 1"));
    r.push_back(text_row<P>(
        "retrieval", "retrieval", "KIND",
        "hbst (binary descriptors), kdtree (fpfh), all (every older map; small sequences); auto: "
        "hbst or kdtree by the pipeline",
        [](const P& p) { return p.method; },
        [](P& p, const std::string& v) { p.method = v; }));  // validate() checks the name
    r.push_back(field_row(&P::exact, "exact-retrieval", "exact_retrieval", "",
                          "HBST votes by the true nearest descriptor (backtracking) instead of one "
                          "leaf"));
    return r;
  }();
  return rows;
}

}  // namespace verifybench
