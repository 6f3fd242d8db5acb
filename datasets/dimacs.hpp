#pragma once
// DIMACS edge format (second DIMACS implementation challenge): "c" comment lines, one
// "p edge N M" (or "p col N M") line, then "e u v" lines with 1-based vertex ids.
// Duplicate edges and self-loops are tolerated (ignored); M is not checked against the edge lines.
#include <cstddef>
#include <map>
#include <string>

#include "core/errors.hpp"
#include "graph/bitgraph.hpp"

namespace verifybench {

/// Throws InputError naming the file, the line and the bad token, or when the adjacency rows of N
/// vertices would exceed `max_bytes`.
BitGraph read_dimacs(const std::string& path, std::size_t max_bytes = std::size_t{4} << 30);

/// MANIFEST.tsv of a DIMACS folder: a header line, then "instance<TAB>n<TAB>m<TAB>omega" rows.
/// Returns instance -> omega; throws InputError naming the line of a malformed row.
std::map<std::string, int> read_manifest(const std::string& path);

}  // namespace verifybench
