#pragma once
// The one way verifybench runs work in parallel: a pool of std::threads that sleep on a condition
// variable between jobs (no spinning on a busy machine), the caller working as thread 0. Work is
// split by index in fixed contiguous blocks, so what each index computes never depends on the
// thread count.
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace verifybench {

/// `requested` threads, 0 meaning every hardware thread; at least 1.
int resolve_threads(int requested);

class WorkerPool {
 public:
  /// `threads` workers in all (resolve_threads applied), threads - 1 of them started here.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int size() const { return static_cast<int>(threads_.size()) + 1; }

  /// body(i) for every i in [0, count): worker k takes the k-th of size() contiguous blocks.
  /// Returns when every call has returned. An exception from body is rethrown here (the first).
  void parallel_for(int count, const std::function<void(int)>& body);

 private:
  void work(int worker);
  void run_block(int worker);

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* body_ = nullptr;
  int count_ = 0;
  long long generation_ = 0;
  int running_ = 0;
  bool quit_ = false;
  std::exception_ptr error_;
};

}  // namespace verifybench
