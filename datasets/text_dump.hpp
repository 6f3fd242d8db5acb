#pragma once
// Reader for plain-text correspondence dumps in the layout of the 3DMatch corr_6614 dump:
//   DIR/corr.txt   one correspondence per line: "xs ys zs xt yt zt" (3D) or "xs ys xt yt" (2D)
//   DIR/label.txt  optional, one 0/1 per line (1 = true inlier), same order as corr.txt
//   DIR/GTmat.txt  optional, (Dim+1)x(Dim+1) homogeneous T_target_source, row-major
// Blank lines and lines starting with '#' are skipped.
#include <stdexcept>
#include <string>
#include <variant>

#include "core/correspondences.hpp"
#include "core/errors.hpp"

namespace verifybench {

using AnySet = std::variant<LabeledSet<2>, LabeledSet<3>>;

/// Reads a dump folder. Throws InputError on a missing folder or corr.txt, a malformed or
/// non-finite value, inconsistent column counts, a label count that differs from the
/// correspondence count, or a ground-truth matrix that is not a rigid motion.
AnySet read_text_dump(const std::string& dir);

}  // namespace verifybench
