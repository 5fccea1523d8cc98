#include "worker_pool.hpp"

#include <algorithm>

namespace finflex::cli {

WorkerPool::WorkerPool(std::size_t workers) {
  for (std::size_t k = 0; k < std::max<std::size_t>(workers, 1); ++k) {
    threads_.emplace_back([this] { work(); });
  }
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  ready_.notify_all();
  for (std::thread& t : threads_) t.join();
}

std::size_t WorkerPool::default_workers() {
  const std::size_t cores = std::thread::hardware_concurrency();
  return std::clamp<std::size_t>(cores > 1 ? cores - 1 : 1, 1, 8);
}

void WorkerPool::work() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, and nothing left
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    task();  // a packaged task: its exception goes to its future
  }
}

}  // namespace finflex::cli
