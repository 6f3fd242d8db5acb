// `verifybench graph`: the correspondence graph of Eq. (1) of one dump, as a DIMACS file, so that
// other maximum clique programs (the peers of ../shared/peers) can search the very graph `clique`
// searches.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <variant>

#include "apps/cli.hpp"
#include "apps/param_options.hpp"
#include "core/timer.hpp"
#include "datasets/dump_format.hpp"
#include "graph/compatibility_graph.hpp"

namespace verifybench {

namespace {

/// Buffered writes to one descriptor; throws std::runtime_error naming `name` on failure.
class FdWriter {
 public:
  FdWriter(int fd, std::string name) : fd_(fd), name_(std::move(name)) { buf_.reserve(kSize); }
  void put(const std::string& s) {
    buf_ += s;
    if (buf_.size() >= kSize) flush();
  }
  /// "e u v\n" with 1-based ids.
  void edge(int u, int v) {
    char line[40] = "e ";  // "e " + two ints of at most 11 characters + " " + "\n"
    char* p = std::to_chars(line + 2, line + 14, u + 1).ptr;
    *p++ = ' ';
    p = std::to_chars(p, p + 12, v + 1).ptr;
    *p++ = '\n';
    buf_.append(line, static_cast<std::size_t>(p - line));
    if (buf_.size() >= kSize) flush();
  }
  void flush() {
    for (std::size_t done = 0; done < buf_.size();) {
      const ssize_t k = ::write(fd_, buf_.data() + done, buf_.size() - done);
      if (k < 0) {
        if (errno == EINTR) continue;
        throw std::runtime_error("cannot write " + name_ + ": " + std::strerror(errno));
      }
      done += static_cast<std::size_t>(k);
    }
    buf_.clear();
  }

 private:
  static constexpr std::size_t kSize = std::size_t{1} << 20;
  int fd_;
  std::string name_;
  std::string buf_;
};

/// Header and every edge {u < v} of g, in row order.
void write_dimacs(FdWriter& w, const BitGraph& g, const std::string& header) {
  w.put(header);
  w.put("p edge " + std::to_string(g.size()) + " " + std::to_string(g.edge_count()) + "\n");
  for (int u = 0; u < g.size(); ++u) {
    const BitGraph::Word* row = g.row(u);
    const int first = (u + 1) / BitGraph::kWordBits;
    for (int k = first; k < g.words(); ++k) {
      BitGraph::Word bits = row[k];
      if (k == first) bits &= ~BitGraph::Word{0} << ((u + 1) % BitGraph::kWordBits);
      while (bits) {
        const int v = k * BitGraph::kWordBits + __builtin_ctzll(bits);
        bits &= bits - 1;
        w.edge(u, v);
      }
    }
  }
  w.flush();
}

/// Writes through an exclusively created PATH.tmp.XXXXXX beside PATH, fsynced, then renamed over
/// PATH: a reader never sees half a graph; nothing is left behind on failure.
void write_dimacs_atomic(const std::string& path, const BitGraph& g, const std::string& header) {
  std::string tmp = path + ".tmp.XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  try {
    FdWriter w(fd, path);
    write_dimacs(w, g, header);
    if (::fchmod(fd, 0644) != 0 || ::fsync(fd) != 0) {
      throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    }
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (::close(fd) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
}

}  // namespace

/// Shortest text that reads back as the same double.
std::string shortest(double v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

int cmd_graph(const std::vector<std::string>& args, const std::vector<std::string>&) {
  std::string dir, out;
  SolverParams shape;  // eps, the graph cap and threads: the solvers' own rows (solvers/params.cpp)
  bool overwrite = false, quiet = false;
  Options o;
  o.text("dump", dir, "DIR",
         "dump folder, as `run` reads it: dump.json + matches.tsv, or corr.txt (required)")
      .text("out", out, "G.clq",
            "DIMACS file to write (required; written atomically; '-' = stdout); an existing file "
            "is refused unless --overwrite")
      .flag("overwrite", overwrite, "replace an existing --out file");
  cli::add_rows(o, cli::common_rows({"eps", "max-graph-mb", "threads"}), shape);
  o.flag("quiet", quiet, "no summary line on stderr");
  if (o.parse_or_help(
          args,
          "usage: verifybench graph --dump DIR [--eps M] --out G.clq [--overwrite]\n"
          "Writes the correspondence graph of Eq. (1) of the dump in DIMACS edge format: vertex i\n"
          "(1-based) = correspondence i in the dump's order, an edge {i, j} when\n"
          "  | ||m_i - m_j|| - ||q_i - q_j|| | < eps   (double precision).\n"
          "It is exactly the graph the `clique` solvers (clique, clique-<algorithm>) build before\n"
          "their search: the full graph, before any pruning inside the clique algorithm (auto's\n"
          "greedy starts and k-core pruning run inside the search, as they do in `verifybench\n"
          "dimacs` on this file). The dimension comes from the dump. `c` comment lines name the\n"
          "dump, eps, dim, n and m.\n"))
    return 0;
  o.require("dump");
  o.require("out");
  const double eps = shape.eps;
  const std::size_t max_bytes = shape.max_graph_bytes;
  const int threads = shape.threads;
  const bool to_stdout = out == "-";
  if (!to_stdout) {
    std::error_code ec;
    const auto st = std::filesystem::symlink_status(out, ec);
    if (std::filesystem::exists(st) && !overwrite) {
      throw UsageError("--out: " + out + " exists (--overwrite replaces it)");
    }
    try {
      check_report_path(out);  // not a directory, link or device; its folder writable
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--out: ") + e.what());
    }
  }
  if (!std::filesystem::is_directory(dir)) {
    throw InputError("--dump: " + dir + ": no such dump folder");
  }
  const Dump dump = read_dump(dir);
  StopWatch clock;
  const auto [graph, dim] = std::visit(
      [&](const auto& s) {
        validate(s);
        return std::make_pair(build_compatibility_graph(
                                  s.corr, GraphParams{eps, max_bytes, threads, 0.0}),
                              static_cast<int>(s.corr.source.rows()));
      },
      dump.set);
  const double build_ms = clock.ms();
  const long long m = graph.edge_count();
  const std::string eps_text = shortest(eps);
  const std::string header =
      "c verifybench graph: the correspondence graph of Eq. (1), an edge {i, j} when\n"
      "c   | ||m_i - m_j|| - ||q_i - q_j|| | < eps; vertex i = correspondence i (1-based)\n"
      "c dump " + dir + "\n"
      "c eps " + eps_text + "\n"
      "c dim " + std::to_string(dim) + "\n"
      "c n " + std::to_string(graph.size()) + "\n"
      "c m " + std::to_string(m) + "\n";
  if (to_stdout) {
    FdWriter w(STDOUT_FILENO, "stdout");
    write_dimacs(w, graph, header);
  } else {
    write_dimacs_atomic(out, graph, header);
    std::cout << out << "\n";
  }
  if (!quiet) {
    std::cerr << "graph: " << dir << " eps " << eps_text << ": n " << graph.size() << ", m "
              << m << ", density "
              << (graph.size() > 1 ? 2.0 * static_cast<double>(m) /
                                         (static_cast<double>(graph.size()) * (graph.size() - 1))
                                   : 0.0)
              << ", built in " << build_ms << " ms\n";
  }
  return 0;
}

}  // namespace verifybench
