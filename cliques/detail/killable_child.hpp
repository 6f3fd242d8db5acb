#pragma once
// The peers' harness: neither cliquer nor igraph can be stopped promptly from outside (cliquer asks
// its time function only between top-level vertices; igraph_largest_cliques does not poll its
// interruption handler), so each runs in a forked child that is killed at the deadline: a peer
// past the limit returns no clique, with status time_limit. The fork costs about a millisecond and
// is part of the peer's measured time.
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
#include <vector>

#include "cliques/max_clique.hpp"
#include "core/timer.hpp"

namespace verifybench::detail {

inline bool write_all(int fd, const void* data, std::size_t bytes) {
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

inline CliqueSearchResult peer_result(std::optional<std::vector<int>> clique, int n) {
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

}  // namespace verifybench::detail
