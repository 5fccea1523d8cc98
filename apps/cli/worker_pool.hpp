// Threads for the work of a frame that the GPU does not need back (PNG encoding,
// masks and annotations): tasks run in any order on any worker, and each task's future
// gives its result (or rethrows its exception) to the one thread that submitted it,
// which takes them in submission order, so what is written stays in frame order.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

namespace finflex::cli {

class WorkerPool {
 public:
  // `workers` threads (at least 1).
  explicit WorkerPool(std::size_t workers);
  // Runs what is queued, then joins the workers.
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  std::size_t size() const { return threads_.size(); }

  template <typename Task>
  auto submit(Task task) -> std::future<decltype(task())> {
    using Result = decltype(task());
    auto packaged = std::make_shared<std::packaged_task<Result()>>(std::move(task));
    std::future<Result> future = packaged->get_future();
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      queue_.emplace_back([packaged] { (*packaged)(); });
    }
    ready_.notify_one();
    return future;
  }

  // The workers for a machine: its cores but one (the frame loop's), 1 to 8.
  static std::size_t default_workers();

 private:
  void work();
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace finflex::cli
