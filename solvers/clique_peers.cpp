// Peers in the same registry, run by the same harness: Debian's libcliquer (Ostergard's algorithm,
// through a C shim) and libigraph's igraph_largest_cliques.
//
// Neither library can be stopped promptly from outside (cliquer asks its time function only between
// top-level vertices; igraph_largest_cliques does not poll its interruption handler), so each runs
// in a forked child that is killed at the deadline: a peer past the limit returns no clique, with
// status time_limit. The fork costs about a millisecond and is part of the peer's measured time.
#include <igraph/igraph.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "solvers/bbmc.hpp"
#include "solvers/cliquer_shim.h"
#include "solvers/max_clique.hpp"

namespace verifybench {

namespace {

bool write_all(int fd, const void* data, std::size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t k = ::write(fd, p, bytes);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    bytes -= static_cast<std::size_t>(k);
  }
  return true;
}

/// Runs `compute` in a child process; returns its clique, or nullopt when the deadline passed first
/// (the child is killed). Throws when the child fails.
template <class F>
std::optional<std::vector<int>> run_in_child(SteadyClock::time_point deadline, F compute) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("peer: pipe() failed");
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("peer: fork() failed");
  if (pid == 0) {
    ::close(fds[0]);
    const std::vector<int> clique = compute();
    const int size = static_cast<int>(clique.size());
    const bool ok = write_all(fds[1], &size, sizeof size) &&
                    write_all(fds[1], clique.data(), clique.size() * sizeof(int));
    ::_exit(ok ? 0 : 1);
  }
  ::close(fds[1]);
  std::vector<char> bytes;
  bool timed_out = false;
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - SteadyClock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd pfd{fds[0], POLLIN, 0};
    const int ready = ::poll(&pfd, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    char buf[65536];
    const ssize_t k = ::read(fds[0], buf, sizeof buf);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) break;  // the child closed its end: done
    bytes.insert(bytes.end(), buf, buf + k);
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) return std::nullopt;
  int size = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || bytes.size() < sizeof size) {
    throw std::runtime_error("peer: the child process failed");
  }
  std::memcpy(&size, bytes.data(), sizeof size);
  if (size < 0 || bytes.size() != sizeof size + static_cast<std::size_t>(size) * sizeof(int)) {
    throw std::runtime_error("peer: truncated result from the child process");
  }
  std::vector<int> clique(static_cast<std::size_t>(size));
  std::memcpy(clique.data(), bytes.data() + sizeof size, clique.size() * sizeof(int));
  return clique;
}

CliqueSearchResult peer_result(std::optional<std::vector<int>> clique, int n) {
  CliqueSearchResult r;
  r.stopped = !clique.has_value();
  r.optimal = !r.stopped;
  if (clique) {
    r.clique = std::move(*clique);
    std::sort(r.clique.begin(), r.clique.end());
  }
  r.upper_bound = n;
  return r;
}

CliqueSearchResult run_cliquer(const BitGraph& g, const CliqueSearchParams& p) {
  static_assert(sizeof(unsigned long long) == sizeof(BitGraph::Word));
  return peer_result(run_in_child(deadline_after(p.time_limit_s),
                                  [&] {
                                    std::vector<int> out(static_cast<std::size_t>(g.size()));
                                    const int size = vb_cliquer_max_clique(
                                        g.size(),
                                        reinterpret_cast<const unsigned long long*>(g.row(0)),
                                        g.words(), out.data());
                                    if (size < 0) ::_exit(2);
                                    out.resize(static_cast<std::size_t>(size));
                                    return out;
                                  }),
                     g.size());
}

std::vector<int> igraph_clique(const BitGraph& g) {
  igraph_set_error_handler(igraph_error_handler_ignore);  // return codes instead of abort()
  igraph_set_warning_handler(igraph_warning_handler_ignore);
  std::vector<int> clique;
  if (g.size() == 0) return clique;
  igraph_vector_int_t edges;
  igraph_vector_int_init(&edges, 0);
  for (int i = 0; i < g.size(); ++i) {
    detail::for_each_bit(g.row(i), g.words(), [&](int j) {
      if (j > i) {
        igraph_vector_int_push_back(&edges, i);
        igraph_vector_int_push_back(&edges, j);
      }
    });
  }
  igraph_t graph;
  igraph_create(&graph, &edges, g.size(), IGRAPH_UNDIRECTED);
  igraph_vector_int_destroy(&edges);
  igraph_vector_int_list_t cliques;
  igraph_vector_int_list_init(&cliques, 0);
  if (igraph_largest_cliques(&graph, &cliques) != IGRAPH_SUCCESS) ::_exit(3);
  if (igraph_vector_int_list_size(&cliques) > 0) {
    const igraph_vector_int_t* c = igraph_vector_int_list_get_ptr(&cliques, 0);
    for (igraph_integer_t k = 0; k < igraph_vector_int_size(c); ++k) {
      clique.push_back(static_cast<int>(VECTOR(*c)[k]));
    }
  }
  igraph_vector_int_list_destroy(&cliques);
  igraph_destroy(&graph);
  return clique;
}

CliqueSearchResult run_igraph(const BitGraph& g, const CliqueSearchParams& p) {
  return peer_result(run_in_child(deadline_after(p.time_limit_s), [&] { return igraph_clique(g); }),
                     g.size());
}

}  // namespace

void register_clique_peers() {
  CliqueAlgorithms::add({"cliquer",
                         "peer: Debian libcliquer 1.21 (Ostergard), default options, via a C shim",
                         true, run_cliquer});
  CliqueAlgorithms::add(
      {"igraph", "peer: Debian libigraph 0.10 igraph_largest_cliques", true, run_igraph});
}

}  // namespace verifybench
