#include "gate_events.hpp"

#include <system_error>
#include <utility>

#include "finflex/context.hpp"

namespace finflex::detail {

GateEvents::GateEvents(const cl::Context& context) : context_(context) {}

GateEvents::~GateEvents() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (helper_.joinable()) helper_.join();
}

cl::UserEvent GateEvents::take() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!ready_.empty()) {
      cl::UserEvent event = std::move(ready_.back());
      ready_.pop_back();
      return event;
    }
  }
  cl_int status = CL_SUCCESS;
  cl::UserEvent event(context_, &status);
  check_cl(status, "clCreateUserEvent");
  return event;
}

void GateEvents::top_up() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (wanted_ || stopping_ || ready_.size() >= kLow) return;
    if (!helper_.joinable()) {
      try {
        helper_ = std::thread([this] { make_ahead(); });
      } catch (const std::system_error&) {
        return;  // no thread to be had: take() makes each event itself
      }
    }
    wanted_ = true;
  }
  wake_.notify_one();
}

void GateEvents::make_ahead() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return wanted_ || stopping_; });
    if (stopping_) return;
    while (!stopping_ && ready_.size() < kReady) {
      lock.unlock();
      cl_int status = CL_SUCCESS;
      cl::UserEvent event(context_, &status);
      lock.lock();
      if (status != CL_SUCCESS) break;  // take() makes its own, and names the failure
      ready_.push_back(std::move(event));
    }
    wanted_ = false;
  }
}

}  // namespace finflex::detail
