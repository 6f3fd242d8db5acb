#include "datasets/text_dump.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/transform.hpp"

namespace verifybench {

namespace {

namespace fs = std::filesystem;

struct Row {
  int line;
  std::vector<double> values;
};

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  input_error(file, line, what);
}

/// Splits a whitespace-separated numeric file into rows; `name_of(col)` names fields in errors.
template <class NameOf>
std::vector<Row> read_rows(const std::string& file, NameOf name_of) {
  std::ifstream in(file);
  if (!in) fail(file, 0, "cannot open file");
  std::vector<Row> rows;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream fields(text);
    Row row{line, {}};
    std::string token;
    while (fields >> token) {
      const int col = static_cast<int>(row.values.size());
      const ParsedReal v = parse_real_token(token);
      if (v.error == NumberError::not_a_number) {
        fail(file, line, "field " + name_of(col) + ": '" + token + "' is not a number");
      }
      if (v.error == NumberError::not_finite) {
        fail(file, line, "field " + name_of(col) + ": '" + token + "' is not finite");
      }
      row.values.push_back(v.value);
    }
    rows.push_back(std::move(row));
  }
  if (in.bad()) fail(file, 0, "read error");
  return rows;
}

template <int Dim>
LabeledSet<Dim> to_set(const std::string& file, const std::vector<Row>& rows) {
  LabeledSet<Dim> set;
  const auto n = static_cast<Eigen::Index>(rows.size());
  set.corr.source.resize(Dim, n);
  set.corr.target.resize(Dim, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Row& r = rows[static_cast<std::size_t>(i)];
    if (r.values.size() != 2 * Dim) {
      fail(file, r.line,
           "expected " + std::to_string(2 * Dim) + " fields (as on line " +
               std::to_string(rows.front().line) + "), found " + std::to_string(r.values.size()));
    }
    for (int d = 0; d < Dim; ++d) {
      set.corr.source(d, i) = r.values[static_cast<std::size_t>(d)];
      set.corr.target(d, i) = r.values[static_cast<std::size_t>(Dim + d)];
    }
  }
  return set;
}

std::vector<std::uint8_t> read_labels(const std::string& file, std::size_t expected) {
  std::vector<std::uint8_t> labels;
  for (const Row& r : read_rows(file, [](int) { return std::string("label"); })) {
    if (r.values.size() != 1 || (r.values[0] != 0.0 && r.values[0] != 1.0)) {
      fail(file, r.line, "field label: expected a single 0 or 1");
    }
    labels.push_back(r.values[0] == 1.0 ? 1 : 0);
  }
  if (labels.size() != expected) {
    fail(file, 0,
         "has " + std::to_string(labels.size()) + " labels but corr.txt has " +
             std::to_string(expected) + " correspondences");
  }
  return labels;
}

template <int Dim>
PublishedRigid<Dim> read_transform(const std::string& file) {
  constexpr int H = Dim + 1;
  const auto rows = read_rows(file, [](int col) { return "column " + std::to_string(col + 1); });
  if (rows.size() != H) {
    fail(file, 0,
         "expected a " + std::to_string(H) + "x" + std::to_string(H) + " matrix for a " +
             std::to_string(Dim) + "D dump, found " + std::to_string(rows.size()) + " rows");
  }
  Eigen::Matrix<double, H, H> M;
  for (int r = 0; r < H; ++r) {
    if (rows[r].values.size() != H) {
      fail(file, rows[r].line,
           "expected " + std::to_string(H) + " fields, found " +
               std::to_string(rows[r].values.size()));
    }
    for (int c = 0; c < H; ++c) M(r, c) = rows[r].values[static_cast<std::size_t>(c)];
  }
  if (!M.allFinite()) fail(file, 0, "the matrix has a non-finite entry");
  Eigen::Matrix<double, 1, H> last = Eigen::Matrix<double, 1, H>::Zero();
  last(Dim) = 1.0;
  if ((M.row(Dim) - last).norm() > 1e-6) fail(file, rows[Dim].line, "last row must be 0 ... 0 1");
  return published_rigid<Dim>(M, file);
}

template <int Dim>
AnySet finish(const std::string& dir, const std::string& corr_file, const std::vector<Row>& rows) {
  LabeledSet<Dim> set = to_set<Dim>(corr_file, rows);
  const fs::path labels = fs::path(dir) / "label.txt";
  const fs::path gt = fs::path(dir) / "GTmat.txt";
  if (fs::exists(labels)) set.truth.labels = read_labels(labels.string(), rows.size());
  if (fs::exists(gt)) {
    const PublishedRigid<Dim> T = read_transform<Dim>(gt.string());
    set.truth.T_target_source = T.T;
    set.truth.rotation_residual = T.rotation_residual;
  }
  return set;
}

}  // namespace

AnySet read_text_dump(const std::string& dir) {
  if (fs::is_regular_file(dir)) {
    const fs::path folder = fs::path(dir).has_parent_path() ? fs::path(dir).parent_path() : ".";
    fail(dir, 0,
         "is a file; --dump takes the dump's folder (" + folder.string() +
             "), which holds dump.json + matches.tsv or corr.txt");
  }
  if (!fs::is_directory(dir)) fail(dir, 0, "dump folder does not exist or is not a folder");
  const std::string corr_file = (fs::path(dir) / "corr.txt").string();
  if (!fs::exists(corr_file)) fail(corr_file, 0, "missing (a dump folder needs corr.txt)");
  const auto rows =
      read_rows(corr_file, [](int col) { return "column " + std::to_string(col + 1); });
  if (rows.empty()) fail(corr_file, 0, "no correspondences (empty set)");
  const std::size_t columns = rows.front().values.size();
  if (columns == 6) return finish<3>(dir, corr_file, rows);
  if (columns == 4) return finish<2>(dir, corr_file, rows);
  fail(
      corr_file, rows.front().line,
      "expected 6 fields (xs ys zs xt yt zt) or 4 (xs ys xt yt), found " + std::to_string(columns));
}

}  // namespace verifybench
