#pragma once
// verifybench dump format, version 1: one folder per correspondence set.
//   DIR/dump.json    {"format": "verifybench-dump", "version": 1, "dim": 2|3, "count": n,
//                     "columns": ["xs","ys",("zs"),"xt","yt",("zt"),("score"),("label")],
//                     "T_target_source": row-major (dim+1)^2 | null,
//                     "label_threshold": metres | null, "provenance": {...},
//                     "clouds": {...} (optional: the two clouds, datasets/dump_clouds.hpp)}
//   DIR/matches.tsv  one line per correspondence, tab-separated, in the order of "columns";
//                    a first line "# " + the column names. score: higher = better (e.g. minus the
//                    Hamming distance); label: 1 = inlier (ground-truth residual <
//                    label_threshold).
// From Python: json.load(open("DIR/dump.json")); numpy.loadtxt("DIR/matches.tsv").
#include <nlohmann/json.hpp>
#include <cstdint>
#include <optional>
#include <string>

#include "datasets/dump_clouds.hpp"
#include "datasets/text_dump.hpp"

namespace verifybench {

struct Dump {
  AnySet set;                             ///< points, optional scores, truth
  std::optional<double> label_threshold;  ///< how labels were derived, when they were
  nlohmann::json provenance = nlohmann::json::object();  ///< inputs, parameters, counts, timings
  std::optional<DumpClouds> clouds;  ///< `extract --keep-clouds`: for the dense check
};

constexpr int kDumpFormatVersion = 1;
/// dump.json limits: metadata only, so small and shallow (a larger or deeper one is refused).
constexpr std::uintmax_t kMaxDumpJsonBytes = std::uintmax_t{16} << 20;
constexpr int kMaxDumpJsonDepth = 64;

/// Writes DIR atomically: into a sibling temporary folder, renamed to DIR at the end. Refuses an
/// existing DIR (nothing is overwritten). Throws InputError (bad set) or std::runtime_error (I/O).
void write_dump(const std::string& dir, const Dump& dump);

/// Reads a folder in this format (dump.json present) or in the plain-text layout of
/// read_text_dump (corr.txt). Throws InputError naming file, line, field and value.
Dump read_dump(const std::string& dir);

/// The expected decision of dump DIR from MANIFEST.tsv beside it (a corpus manifest: a header with
/// `name` and `expected` columns, as scripts/corpus writes): true for positive, false for
/// negative; nullopt without a manifest, without those columns or without a row for DIR. Throws
/// InputError naming the line of an expected value that is neither.
std::optional<bool> manifest_expected(const std::string& dir);

}  // namespace verifybench
