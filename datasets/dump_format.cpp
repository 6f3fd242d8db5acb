#include "datasets/dump_format.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/transform.hpp"

namespace verifybench {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
  input_error(file.string(), 0, what);
}

template <int Dim>
std::vector<std::string> columns(const LabeledSet<Dim>& s) {
  std::vector<std::string> c{"xs", "ys"};
  if (Dim == 3) c.push_back("zs");
  c.insert(c.end(), {"xt", "yt"});
  if (Dim == 3) c.push_back("zt");
  if (!s.corr.score.empty()) c.push_back("score");
  if (!s.truth.labels.empty()) c.push_back("label");
  return c;
}

template <int Dim>
void write_set(const fs::path& tmp, const LabeledSet<Dim>& s, const Dump& dump) {
  validate(s);
  const auto cols = columns(s);
  json meta = {
      {"format", "verifybench-dump"},
      {"version", kDumpFormatVersion},
      {"dim", Dim},
      {"count", s.corr.size()},
      {"columns", cols},
      {"T_target_source", nullptr},
      {"label_threshold", dump.label_threshold ? json(*dump.label_threshold) : json(nullptr)},
      {"provenance", dump.provenance}};
  if (s.truth.T_target_source) {
    std::vector<double> m;
    const auto M = s.truth.T_target_source->matrix();
    for (int r = 0; r <= Dim; ++r)
      for (int c = 0; c <= Dim; ++c) m.push_back(M(r, c));
    meta["T_target_source"] = m;
  }
  if (dump.clouds) meta["clouds"] = write_dump_clouds(tmp, *dump.clouds);
  std::ofstream js(tmp / "dump.json");
  js << meta.dump(2) << "\n";
  std::ofstream tsv(tmp / "matches.tsv");
  // A tab-separated header line of the column names: pandas.read_csv(sep="\t") reads it as is.
  for (std::size_t k = 0; k < cols.size(); ++k) tsv << (k ? "\t" : "") << cols[k];
  tsv << "\n" << std::setprecision(17);
  for (Eigen::Index i = 0; i < s.corr.size(); ++i) {
    for (int d = 0; d < Dim; ++d) tsv << s.corr.source(d, i) << "\t";
    for (int d = 0; d < Dim; ++d) tsv << s.corr.target(d, i) << (d + 1 < Dim ? "\t" : "");
    if (!s.corr.score.empty()) tsv << "\t" << s.corr.score[static_cast<std::size_t>(i)];
    if (!s.truth.labels.empty()) tsv << "\t" << int(s.truth.labels[static_cast<std::size_t>(i)]);
    tsv << "\n";
  }
  js.flush();
  tsv.flush();
  if (!js || !tsv) throw std::runtime_error("cannot write dump files in " + tmp.string());
}

double number(const std::string& token, const fs::path& file, std::size_t line,
              const std::string& field) {
  const ParsedReal v = parse_real_token(token);
  if (v.error == NumberError::none) return v.value;
  fail(file, "line " + std::to_string(line) + ": field " + field + " = '" + token +
                 "' is not a finite number");
}

template <int Dim>
Dump read_set(const fs::path& dir, const json& meta) {
  const fs::path file = dir / "matches.tsv";
  Dump dump;
  LabeledSet<Dim> s;
  std::vector<std::string> cols;
  try {
    cols = meta.at("columns").get<std::vector<std::string>>();
  } catch (const std::exception&) {
    fail(dir / "dump.json", "field columns is missing or not a list of names");
  }
  LabeledSet<Dim> probe;
  probe.corr.score.push_back(0);
  probe.truth.labels.push_back(0);
  const auto full = columns(probe);
  // Accepted: the coordinate columns, then optionally score, then optionally label.
  const std::size_t base = 2 * Dim;
  const bool has_score = cols.size() > base && cols[base] == "score";
  const bool has_label = !cols.empty() && cols.back() == "label" && cols.size() > base;
  const std::size_t expected = base + has_score + has_label;
  if (cols.size() != expected || !std::equal(cols.begin(), cols.begin() + base, full.begin())) {
    fail(dir / "dump.json", "columns do not match dim " + std::to_string(Dim) + " (expected xs ys" +
                                (Dim == 3 ? " zs" : "") + " xt yt" + (Dim == 3 ? " zt" : "") +
                                " [score] [label])");
  }
  std::ifstream in(file);
  if (!in) fail(file, "cannot open");
  std::vector<std::array<double, 6>> pts;
  std::string text;
  std::size_t line = 0;
  bool header_seen = false;
  while (std::getline(in, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty() || text[0] == '#') continue;  // blank, or the "# xs ys ..." header before v1.1
    std::istringstream row(text);
    std::vector<std::string> tokens;
    for (std::string t; row >> t;) tokens.push_back(t);
    if (!header_seen && pts.empty() && tokens == cols) {  // the column-name header
      header_seen = true;
      continue;
    }
    if (tokens.size() != cols.size()) {
      fail(file, "line " + std::to_string(line) + ": " + std::to_string(tokens.size()) +
                     " fields; expected " + std::to_string(cols.size()) + " (" +
                     std::to_string(pts.size() + 1) + "th correspondence)");
    }
    std::array<double, 6> p{};
    for (std::size_t k = 0; k < base; ++k) p[k] = number(tokens[k], file, line, cols[k]);
    pts.push_back(p);
    if (has_score) s.corr.score.push_back(number(tokens[base], file, line, "score"));
    if (has_label) {
      const std::string& l = tokens.back();
      if (l != "0" && l != "1") {
        fail(file, "line " + std::to_string(line) + ": field label = '" + l + "' is not 0 or 1");
      }
      s.truth.labels.push_back(l == "1");
    }
  }
  if (pts.empty()) fail(file, "no correspondences (empty set)");  // as the text reader says
  if (meta.contains("count") && meta["count"].is_number_integer() &&
      meta["count"].get<long long>() != static_cast<long long>(pts.size())) {
    fail(file, std::to_string(pts.size()) +
                   " correspondences but dump.json says count = " + meta["count"].dump());
  }
  s.corr.source.resize(Dim, static_cast<Eigen::Index>(pts.size()));
  s.corr.target.resize(Dim, static_cast<Eigen::Index>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    for (int d = 0; d < Dim; ++d) {
      s.corr.source(d, static_cast<Eigen::Index>(i)) = pts[i][static_cast<std::size_t>(d)];
      s.corr.target(d, static_cast<Eigen::Index>(i)) = pts[i][static_cast<std::size_t>(Dim + d)];
    }
  }
  if (meta.contains("T_target_source") && !meta["T_target_source"].is_null()) {
    std::vector<double> m;
    try {
      m = meta["T_target_source"].get<std::vector<double>>();
    } catch (const std::exception&) {
      fail(dir / "dump.json", "field T_target_source is not a list of numbers");
    }
    if (m.size() != static_cast<std::size_t>((Dim + 1) * (Dim + 1))) {
      fail(dir / "dump.json", "field T_target_source has " + std::to_string(m.size()) +
                                  " numbers; expected " + std::to_string((Dim + 1) * (Dim + 1)));
    }
    Eigen::Matrix<double, Dim + 1, Dim + 1> M;
    for (int r = 0; r <= Dim; ++r)
      for (int c = 0; c <= Dim; ++c) M(r, c) = m[static_cast<std::size_t>(r * (Dim + 1) + c)];
    const PublishedRigid<Dim> T =
        published_rigid<Dim>(M, (dir / "dump.json").string() + ": field T_target_source");
    s.truth.T_target_source = T.T;
    s.truth.rotation_residual = T.rotation_residual;
  }
  try {
    validate(s);
  } catch (const std::invalid_argument& e) {
    fail(file, e.what());
  }
  dump.set = std::move(s);
  if (meta.contains("label_threshold") && meta["label_threshold"].is_number()) {
    dump.label_threshold = meta["label_threshold"].get<double>();
  }
  if (meta.contains("provenance")) dump.provenance = meta["provenance"];
  if (meta.contains("clouds") && !meta["clouds"].is_null()) {
    dump.clouds = read_dump_clouds(dir, meta["clouds"]);
  }
  return dump;
}

}  // namespace

void write_dump(const std::string& dir, const Dump& dump) {
  const fs::path target(dir);
  if (fs::exists(target)) {
    throw std::runtime_error("dump folder " + dir + " exists; remove it or choose another");
  }
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(parent)) {
    throw std::runtime_error("cannot write dump " + dir + ": no folder " + parent.string());
  }
  const fs::path tmp =
      parent / (target.filename().string() + ".partial-" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directory(tmp);
  try {
    std::visit([&](const auto& s) { write_set(tmp, s, dump); }, dump.set);
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(tmp, ec);
    throw;
  }
}

Dump read_dump(const std::string& dir) {
  const fs::path root(dir);
  const fs::path meta_file = root / "dump.json";
  if (!fs::exists(meta_file)) {
    Dump d;
    d.set = read_text_dump(dir);  // the plain-text layout (corr.txt, label.txt, GTmat.txt)
    return d;
  }
  // dump.json holds metadata only (the points are in matches.tsv): bounded in size and nesting, so
  // that a hostile file cannot exhaust memory or the stack (copying JSON recurses).
  std::error_code size_error;
  const auto bytes = fs::file_size(meta_file, size_error);
  if (size_error) fail(meta_file, "cannot read: " + size_error.message());
  if (bytes > kMaxDumpJsonBytes) {
    fail(meta_file, "is " + std::to_string(bytes) + " bytes; dump.json holds metadata only (at most " +
                        std::to_string(kMaxDumpJsonBytes) + ")");
  }
  json meta;
  try {
    std::ifstream in(meta_file);
    meta = json::parse(in, [](int depth, json::parse_event_t, json&) {
      if (depth > kMaxDumpJsonDepth) {
        throw std::length_error("nesting deeper than " + std::to_string(kMaxDumpJsonDepth) +
                                " levels");
      }
      return true;
    });
  } catch (const std::exception& e) {
    fail(meta_file, std::string("not valid JSON: ") + e.what());
  }
  if (!meta.is_object() || meta.value("format", "") != "verifybench-dump") {
    fail(meta_file, "field format is not \"verifybench-dump\"");
  }
  if (!meta.contains("version") || !meta["version"].is_number_integer() ||
      meta["version"].get<long long>() != kDumpFormatVersion) {
    fail(meta_file,
         "field version = " + (meta.contains("version") ? meta["version"].dump() : "missing") +
             "; this build reads version " + std::to_string(kDumpFormatVersion));
  }
  const long long dim =
      meta.contains("dim") && meta["dim"].is_number_integer() ? meta["dim"].get<long long>() : 0;
  try {
    if (dim == 2) return read_set<2>(root, meta);
    if (dim == 3) return read_set<3>(root, meta);
  } catch (const json::exception& e) {  // a field of the wrong JSON type
    fail(meta_file, std::string("a field has the wrong type: ") + e.what());
  }
  fail(meta_file, "field dim = " + (meta.contains("dim") ? meta["dim"].dump() : "missing") +
                      "; expected 2 or 3");
}

}  // namespace verifybench

namespace verifybench {

std::optional<bool> manifest_expected(const std::string& dir) {
  fs::path root(dir);
  if (root.filename().empty()) root = root.parent_path();  // "DIR/"
  const fs::path manifest = fs::absolute(root).parent_path() / "MANIFEST.tsv";
  std::ifstream in(manifest);
  if (!in) return std::nullopt;
  auto split = [](const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, '\t');) cells.push_back(c);
    return cells;
  };
  std::string line;
  if (!std::getline(in, line)) return std::nullopt;
  const auto header = split(line);
  const auto name_col = std::find(header.begin(), header.end(), "name") - header.begin();
  const auto exp_col = std::find(header.begin(), header.end(), "expected") - header.begin();
  if (name_col == static_cast<long>(header.size()) || exp_col == static_cast<long>(header.size())) {
    return std::nullopt;  // not a corpus manifest (e.g. a DIMACS one)
  }
  const std::string name = root.filename().string();
  for (int number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto cells = split(line);
    if (cells.size() <= static_cast<std::size_t>(std::max(name_col, exp_col))) continue;
    if (cells[static_cast<std::size_t>(name_col)] != name) continue;
    const std::string& v = cells[static_cast<std::size_t>(exp_col)];
    if (v == "positive") return true;
    if (v == "negative") return false;
    input_error(manifest.string(), number,
                "field expected = '" + v + "' is invalid; expected positive or negative");
  }
  return std::nullopt;
}

}  // namespace verifybench
