#include "frontend/hbst.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace verifybench {

struct HbstTree::Node {
  int bit = -1;                    ///< split bit; -1 for a leaf
  std::unique_ptr<Node> child[2];  ///< by the value of `bit`
  std::vector<int> ids;            ///< leaf: descriptor ids
  std::vector<bool> used;          ///< bits already split on along the path
};

HbstTree::HbstTree(int bits, HbstParams params)
    : params_(params), descriptors_(bits), root_(std::make_unique<Node>()) {
  if (bits <= 0 || params.max_leaf_size <= 0 || params.max_depth < 0) {
    throw std::invalid_argument("HbstTree: bits and max_leaf_size must be > 0");
  }
  root_->used.assign(static_cast<std::size_t>(bits), false);
}

HbstTree::~HbstTree() = default;

void HbstTree::insert(const BinaryDescriptors& set) {
  if (set.bits != descriptors_.bits) {
    throw std::invalid_argument("HbstTree: descriptors of " + std::to_string(set.bits) +
                                " bits into a tree of " + std::to_string(descriptors_.bits));
  }
  for (int i = 0; i < set.size(); ++i) {
    std::copy(set.row(i), set.row(i) + set.words(), descriptors_.add());
    insert_one(descriptors_.size() - 1);
  }
}

void HbstTree::insert_one(int id) {
  Node* node = root_.get();
  int depth = 0;
  while (node->bit >= 0) {
    node = node->child[descriptors_.bit(id, node->bit)].get();
    ++depth;
  }
  node->ids.push_back(id);
  if (static_cast<int>(node->ids.size()) > params_.max_leaf_size && depth < params_.max_depth) {
    split(*node, depth);
  }
}

void HbstTree::split(Node& leaf, int depth) {
  // The unused bit with the most even split; none splits (all equal) -> stay a leaf.
  const double half = 0.5 * static_cast<double>(leaf.ids.size());
  int best = -1;
  double best_gap = half;
  for (int b = 0; b < descriptors_.bits; ++b) {
    if (leaf.used[static_cast<std::size_t>(b)]) continue;
    int ones = 0;
    for (int id : leaf.ids) ones += descriptors_.bit(id, b);
    const double gap = std::abs(ones - half);
    if (ones > 0 && ones < static_cast<int>(leaf.ids.size()) && gap < best_gap) {
      best_gap = gap;
      best = b;
    }
  }
  if (best < 0) return;
  leaf.bit = best;
  for (auto& c : leaf.child) {
    c = std::make_unique<Node>();
    c->used = leaf.used;
    c->used[static_cast<std::size_t>(best)] = true;
  }
  for (int id : leaf.ids) leaf.child[descriptors_.bit(id, best)]->ids.push_back(id);
  leaf.ids.clear();
  leaf.ids.shrink_to_fit();
  leaf.used.clear();
  leaf.used.shrink_to_fit();
  for (auto& c : leaf.child) {
    if (static_cast<int>(c->ids.size()) > params_.max_leaf_size && depth + 1 < params_.max_depth) {
      split(*c, depth + 1);
    }
  }
}

int HbstTree::depth() const {
  int deepest = 0;
  auto walk = [&](auto&& self, const Node& n, int d) -> void {
    deepest = std::max(deepest, d);
    if (n.bit >= 0) {
      self(self, *n.child[0], d + 1);
      self(self, *n.child[1], d + 1);
    }
  };
  walk(walk, *root_, 0);
  return deepest;
}

BinaryMatch HbstTree::nearest(const std::uint64_t* query, int max_distance, bool exact) const {
  BinaryMatch best;
  best.distance = max_distance + 1;
  auto visit_leaf = [&](const Node& leaf) {
    scan_nearest(descriptors_, leaf.ids.data(), static_cast<int>(leaf.ids.size()), query, best);
  };
  auto query_bit = [&](int b) { return static_cast<int>((query[b / 64] >> (b % 64)) & 1u); };
  // Descend; in exact mode keep the other branch when its bound (split bits that differ from the
  // query, each costing one) can still reach the threshold.
  auto walk = [&](auto&& self, const Node& n, int bound) -> void {
    if (bound > max_distance || bound > best.distance) return;
    if (n.bit < 0) {
      visit_leaf(n);
      return;
    }
    const int q = query_bit(n.bit);
    self(self, *n.child[q], bound);
    if (exact) self(self, *n.child[1 - q], bound + 1);
  };
  walk(walk, *root_, 0);
  if (best.index < 0) best.distance = 0;
  return best;
}

}  // namespace verifybench
