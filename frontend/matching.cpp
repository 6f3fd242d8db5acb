#include "frontend/matching.hpp"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"

namespace verifybench {

std::string MatchingPolicy::name() const {
  switch (kind) {
    case Kind::nearest:
      return "nearest";
    case Kind::mutual:
      return "mutual";
    case Kind::knn:
      return "knn:" + std::to_string(k);
    case Kind::radius:
      return "radius";
    case Kind::ratio: {
      std::ostringstream out;
      out << "ratio:" << ratio;
      return out.str();
    }
  }
  return "nearest";
}

MatchingPolicy parse_matching(const std::string& text) {
  MatchingPolicy p;
  if (text == "nearest" || text == "k1") return p;
  if (text == "mutual") {
    p.kind = MatchingPolicy::Kind::mutual;
    return p;
  }
  if (text == "radius") {
    p.kind = MatchingPolicy::Kind::radius;
    return p;
  }
  if (text.rfind("knn:", 0) == 0) {
    const auto k = parse_integer_token(text.substr(4));
    if (k && *k >= 1 && *k <= 1000) {
      p.kind = MatchingPolicy::Kind::knn;
      p.k = static_cast<int>(*k);
      return p;
    }
  }
  if (text.rfind("ratio:", 0) == 0) {
    const ParsedReal r = parse_real_token(text.substr(6));
    if (r.error == NumberError::none && r.value > 0.0 && r.value <= 1.0) {
      p.kind = MatchingPolicy::Kind::ratio;
      p.ratio = r.value;
      return p;
    }
  }
  throw std::invalid_argument("matching policy '" + text +
                              "' is not nearest, mutual, knn:K (1 <= K <= 1000), radius or "
                              "ratio:R (0 < R <= 1)");
}

namespace {

bool by_distance(const FeatureMatch& a, const FeatureMatch& b) {
  return a.distance != b.distance ? a.distance < b.distance : a.target < b.target;
}

/// Applies the policy to per-source candidate lists (each ascending by distance, then index, all
/// within the threshold) and, for mutual, the nearest source of each target.
std::vector<FeatureMatch> select(std::vector<std::vector<FeatureMatch>> candidates,
                                 const MatchingPolicy& policy,
                                 const std::vector<int>& nearest_source_of_target) {
  std::vector<FeatureMatch> out;
  for (auto& list : candidates) {
    std::sort(list.begin(), list.end(), by_distance);
    if (list.empty()) continue;
    switch (policy.kind) {
      case MatchingPolicy::Kind::nearest:
        out.push_back(list.front());
        break;
      case MatchingPolicy::Kind::mutual:
        if (nearest_source_of_target[static_cast<std::size_t>(list.front().target)] ==
            list.front().source) {
          out.push_back(list.front());
        }
        break;
      case MatchingPolicy::Kind::knn:
        out.insert(out.end(), list.begin(),
                   list.begin() + std::min<std::ptrdiff_t>(policy.k, list.size()));
        break;
      case MatchingPolicy::Kind::radius:
        out.insert(out.end(), list.begin(), list.end());
        break;
      case MatchingPolicy::Kind::ratio:
        if (list.size() < 2 || list[0].distance < policy.ratio * list[1].distance) {
          out.push_back(list.front());
        }
        break;
    }
  }
  return out;
}

}  // namespace

std::vector<FeatureMatch> match_binary(const BinaryDescriptors& source,
                                       const BinaryDescriptors& target,
                                       const MatchingPolicy& policy, int max_distance) {
  if (source.bits != target.bits) throw std::invalid_argument("descriptor lengths differ");
  const int W = source.words();
  std::vector<std::vector<FeatureMatch>> candidates(static_cast<std::size_t>(source.size()));
  std::vector<int> best_source(static_cast<std::size_t>(target.size()), -1);
  std::vector<int> best_source_d(static_cast<std::size_t>(target.size()),
                                 std::numeric_limits<int>::max());
  for (int i = 0; i < source.size(); ++i) {
    auto& list = candidates[static_cast<std::size_t>(i)];
    for (int j = 0; j < target.size(); ++j) {
      const int d = hamming(source.row(i), target.row(j), W);
      if (d < best_source_d[static_cast<std::size_t>(j)]) {  // ties: lowest source index
        best_source_d[static_cast<std::size_t>(j)] = d;
        best_source[static_cast<std::size_t>(j)] = i;
      }
      if (d <= max_distance) list.push_back({i, j, static_cast<double>(d)});
    }
  }
  return select(std::move(candidates), policy, best_source);
}

namespace {

using Fpfh = pcl::FPFHSignature33;

pcl::PointCloud<Fpfh>::Ptr as_cloud(const RealDescriptors& d) {
  if (d.dims != 33) throw std::invalid_argument("real descriptors must have 33 bins (FPFH)");
  pcl::PointCloud<Fpfh>::Ptr c(new pcl::PointCloud<Fpfh>);
  c->resize(static_cast<std::size_t>(d.size()));
  for (int i = 0; i < d.size(); ++i) std::copy(d.row(i), d.row(i) + 33, (*c)[i].histogram);
  return c;
}

}  // namespace

std::vector<FeatureMatch> match_real(const RealDescriptors& source, const RealDescriptors& target,
                                     const MatchingPolicy& policy, double max_distance) {
  const auto src = as_cloud(source), dst = as_cloud(target);
  std::vector<std::vector<FeatureMatch>> candidates(src->size());
  std::vector<int> best_source(dst->size(), -1);
  if (src->empty() || dst->empty()) return {};
  pcl::KdTreeFLANN<Fpfh> targets;  // exact: FLANN's single k-d tree with eps = 0
  targets.setInputCloud(dst);
  const double max2 = max_distance * max_distance;
  std::vector<int> idx;
  std::vector<float> d2;
  for (std::size_t i = 0; i < src->size(); ++i) {
    auto& list = candidates[i];
    if (policy.kind == MatchingPolicy::Kind::radius) {
      targets.radiusSearch((*src)[i], max_distance, idx, d2);
    } else {
      const int k = policy.kind == MatchingPolicy::Kind::knn     ? policy.k
                    : policy.kind == MatchingPolicy::Kind::ratio ? 2
                                                                 : 1;
      targets.nearestKSearch((*src)[i], std::min<int>(k, static_cast<int>(dst->size())), idx, d2);
    }
    for (std::size_t m = 0; m < idx.size(); ++m) {
      if (d2[m] <= max2) list.push_back({static_cast<int>(i), idx[m], std::sqrt(double(d2[m]))});
    }
  }
  if (policy.kind == MatchingPolicy::Kind::mutual) {
    pcl::KdTreeFLANN<Fpfh> sources;
    sources.setInputCloud(src);
    for (std::size_t j = 0; j < dst->size(); ++j) {
      if (sources.nearestKSearch((*dst)[j], 1, idx, d2) > 0) best_source[j] = idx[0];
    }
  }
  return select(std::move(candidates), policy, best_source);
}

}  // namespace verifybench
