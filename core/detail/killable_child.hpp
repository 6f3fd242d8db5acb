#pragma once
// Library peers that cannot be stopped promptly from outside (cliquer asks its time function only
// between top-level vertices; igraph_largest_cliques does not poll its interruption handler; PCL's
// and Open3D's RANSACs never read a limit) run in a forked child that is killed at the deadline.
// The fork costs about a millisecond and is part of the peer's measured time.
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
#include <type_traits>
#include <vector>

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

/// Runs `compute` (returning a std::vector of a trivially copyable type) in a forked child and
/// returns its vector, or nullopt when the deadline passed first (the child is killed). Whatever
/// the computation sets process-wide (std::srand, OpenMP's thread count) stays in the child.
/// Throws std::runtime_error when the child fails.
template <class F>
auto run_in_child(SteadyClock::time_point deadline, F compute)
    -> std::optional<decltype(compute())> {
  using Vec = decltype(compute());
  using T = typename Vec::value_type;
  static_assert(std::is_trivially_copyable_v<T>);
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("isolated run: pipe() failed");
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("isolated run: fork() failed");
  if (pid == 0) {
    ::close(fds[0]);
    const Vec out = compute();
    const long long size = static_cast<long long>(out.size());
    const bool ok = write_all(fds[1], &size, sizeof size) &&
                    (out.empty() || write_all(fds[1], out.data(), out.size() * sizeof(T)));
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
  long long size = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || bytes.size() < sizeof size) {
    throw std::runtime_error("isolated run: the child process failed");
  }
  std::memcpy(&size, bytes.data(), sizeof size);
  if (size < 0 || bytes.size() != sizeof size + static_cast<std::size_t>(size) * sizeof(T)) {
    throw std::runtime_error("isolated run: truncated result from the child process");
  }
  Vec out(static_cast<std::size_t>(size));
  if (size > 0) std::memcpy(out.data(), bytes.data() + sizeof size, out.size() * sizeof(T));
  return out;
}

}  // namespace verifybench::detail
