#include "datasets/dimacs.hpp"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace verifybench {

namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  input_error(path, line, what);
}

long long parse_id(const std::string& path, int line, const std::string& field,
                   const std::string& token) {
  const auto v = parse_integer_token(token);
  if (!v) fail(path, line, "field " + field + ": '" + token + "' is not an integer");
  return *v;
}

}  // namespace

BitGraph read_dimacs(const std::string& path, std::size_t max_bytes) {
  std::ifstream in(path);
  if (!in) fail(path, 0, "cannot open file");
  BitGraph g;
  bool have_header = false;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    std::istringstream fields(text);
    std::string tag;
    if (!(fields >> tag) || tag == "c") continue;
    if (tag == "p") {
      std::string format, n_text, m_text;
      if (have_header) fail(path, line, "second 'p' line");
      if (!(fields >> format >> n_text >> m_text) || (format != "edge" && format != "col")) {
        fail(path, line, "expected 'p edge N M'");
      }
      const long long n = parse_id(path, line, "N", n_text);
      parse_id(path, line, "M", m_text);
      if (n < 0 || n > 100000000) fail(path, line, "field N: '" + n_text + "' is out of range");
      if (BitGraph::bytes_for(static_cast<std::size_t>(n)) > max_bytes) {
        fail(path, line,
             "a graph of " + n_text + " vertices needs " +
                 std::to_string(BitGraph::bytes_for(static_cast<std::size_t>(n)) >> 20) +
                 " MiB, over the cap of " + std::to_string(max_bytes >> 20) + " MiB");
      }
      g = BitGraph(static_cast<int>(n));
      have_header = true;
    } else if (tag == "e") {
      if (!have_header) fail(path, line, "edge before the 'p edge N M' line");
      std::string u_text, v_text, extra;
      if (!(fields >> u_text >> v_text)) fail(path, line, "expected 'e u v'");
      const long long u = parse_id(path, line, "u", u_text);
      const long long v = parse_id(path, line, "v", v_text);
      for (const auto& [value, token] : {std::pair{u, u_text}, std::pair{v, v_text}}) {
        if (value < 1 || value > g.size()) {
          fail(path, line, "vertex '" + token + "' is outside 1.." + std::to_string(g.size()));
        }
      }
      g.add_edge(static_cast<int>(u - 1), static_cast<int>(v - 1));  // self-loops are ignored
    } else {
      fail(path, line, "unknown line type '" + tag + "' (expected c, p or e)");
    }
  }
  if (in.bad()) fail(path, 0, "read error");
  if (!have_header) fail(path, 0, "no 'p edge N M' line");
  return g;
}

std::map<std::string, int> read_manifest(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, 0, "cannot open file");
  std::map<std::string, int> omega;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (line == 1 || text.empty() || text[0] == '#') continue;  // header
    std::istringstream fields(text);
    std::string name, n, m, w;
    if (!(fields >> name >> n >> m >> w)) fail(path, line, "expected instance, n, m, omega");
    omega[name] = static_cast<int>(parse_id(path, line, "omega", w));
  }
  return omega;
}

}  // namespace verifybench
