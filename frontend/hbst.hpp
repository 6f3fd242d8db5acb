#pragma once
// HBST (Schlegel & Grisetti, RA-L 2018): a binary search tree over binary descriptors. Each inner
// node splits its descriptors on one bit -- the unused bit whose mean over them is closest to 0.5,
// so the split is as even as the data allows -- and leaves hold at most max_leaf_size
// descriptors. Descriptors are inserted incrementally (a full leaf splits); a query descends along
// its own bits to one leaf and compares there (approximate, the paper's mode) or, with `exact`,
// also visits every other branch whose lower bound (the split bits it differs on) is within the
// threshold, which gives exactly the brute-force answer.
#include <memory>
#include <vector>

#include "frontend/binary.hpp"

namespace verifybench {

struct HbstParams {
  int max_leaf_size = 64;  ///< a leaf with more descriptors splits, > 0
  int max_depth = 64;      ///< no split below this depth
};

class HbstTree {
 public:
  HbstTree(int bits, HbstParams params = {});
  ~HbstTree();
  HbstTree(const HbstTree&) = delete;
  HbstTree& operator=(const HbstTree&) = delete;

  /// Adds every descriptor of `set` (same bit length); their ids continue from size().
  void insert(const BinaryDescriptors& set);
  int size() const { return descriptors_.size(); }
  int depth() const;

  /// Nearest stored descriptor within max_distance (ties: lowest id); index -1 when none.
  BinaryMatch nearest(const std::uint64_t* query, int max_distance, bool exact = false) const;

 private:
  struct Node;
  void insert_one(int id);
  void split(Node& leaf, int depth);

  HbstParams params_;
  BinaryDescriptors descriptors_;
  std::unique_ptr<Node> root_;
};

}  // namespace verifybench
