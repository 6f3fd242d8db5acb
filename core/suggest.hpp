#pragma once
// "Did you mean": the nearest known name to a mistyped one, by edit distance (Levenshtein), for
// unknown options, registry names and Python keywords.
#include <algorithm>
#include <string>
#include <vector>

namespace verifybench {

/// Insertions, deletions and substitutions that turn a into b.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1u : 0u)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// The known name nearest to `name`, when it is near enough to be a typo: at most 3 edits and
/// fewer than half of the name's characters; or a known name that starts with `name` (a
/// truncation, e.g. "sc2" for "sc2-pcr"); "" otherwise. Ties go to the first in `known`.
inline std::string nearest_name(const std::string& name, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_d = std::min<std::size_t>(4, (name.size() + 1) / 2);
  for (const std::string& k : known) {
    const std::size_t d = edit_distance(name, k);
    if (d < best_d) best_d = d, best = k;
  }
  if (best.empty() && name.size() >= 2) {
    for (const std::string& k : known) {
      if (k.rfind(name, 0) == 0) return k;
    }
  }
  return best;
}

}  // namespace verifybench
