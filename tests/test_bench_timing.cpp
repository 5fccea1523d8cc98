// The benchmarks' frame loop (bench/support/timing.hpp): one record per timed frame,
// each holding that frame's own kernels, whether each frame is waited for before the
// next is enqueued or the frames run ahead of the device; a reference kernel after
// every frame waited for.
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "support/test_support.hpp"
#include "timing.hpp"

namespace finflex {
namespace {

// A kernel that fills a buffer of 4,096 floats with a value: a frame's stand-in.
class Fill {
 public:
  explicit Fill(Context& context)
      : context_(context), buffer_(context.context(), CL_MEM_READ_WRITE, 4096 * sizeof(float)) {
    cl::Program program(context.context(), R"(
__kernel void fill(__global float* out, const float value) {
  out[get_global_id(0)] = value;
}
)");
    EXPECT_EQ(program.build(), CL_SUCCESS);
    kernel_ = cl::Kernel(program, "fill");
  }

  cl::Event launch(float value) {
    cl::Event done;
    kernel_.setArg(0, buffer_);
    kernel_.setArg(1, value);
    EXPECT_EQ(context_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(4096),
                                                    cl::NDRange(64), nullptr, &done),
              CL_SUCCESS);
    return done;
  }

  // The buffer's first value once the queue has finished.
  float first_value() {
    float value = 0.0f;
    context_.queue().enqueueReadBuffer(buffer_, CL_TRUE, 0, sizeof(float), &value);
    return value;
  }

 private:
  Context& context_;
  cl::Buffer buffer_;
  cl::Kernel kernel_;
};

TEST(BenchTiming, EachFrameRecordsItsOwnKernelsWhetherOrNotFramesRunAhead) {
  Fill fill(test::shared_context());
  for (bool ahead : {false, true}) {
    SCOPED_TRACE(ahead ? "frames ahead" : "frame by frame");
    std::vector<std::size_t> prepared;
    std::size_t enqueued = 0;
    const std::size_t frames = 6;
    // Frame f launches f % 3 + 1 kernels: a record holding another frame's kernels
    // would show in the counts.
    const bench::FrameTimes times = bench::time_frames(
        frames, [&](std::size_t f) { prepared.push_back(f); },
        [&](std::vector<cl::Event>& events) {
          events.clear();
          for (std::size_t k = 0; k < enqueued % 3 + 1; ++k) {
            events.push_back(fill.launch(float(enqueued)));
          }
          ++enqueued;
        },
        ahead);
    EXPECT_EQ(enqueued, frames + 1);  // the warm-up frame, then the timed ones
    EXPECT_EQ(prepared, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6}));
    ASSERT_EQ(times.device.size(), frames);
    ASSERT_EQ(times.host.size(), frames);
    ASSERT_EQ(times.kernels.size(), frames);
    for (std::size_t f = 1; f <= frames; ++f) {
      EXPECT_EQ(times.kernels[f - 1].size(), f % 3 + 1) << "frame " << f;
      EXPECT_GT(times.device[f - 1], 0.0) << "frame " << f;
    }
  }
  EXPECT_EQ(fill.first_value(), 6.0f);  // every frame ran, the last one last
}

// A reference kernel runs after every frame waited for (the warm-up's too) and is
// timed on its own; each timed frame follows an untimed one (its lead) and each timed
// reference an untimed reference; the enqueue callback is told which frames are timed.
// With frames ahead no reference runs.
TEST(BenchTiming, AReferenceKernelRunsAfterEveryFrameWaitedFor) {
  Fill fill(test::shared_context());
  std::vector<std::string> order;  // "frame" or "reference", as enqueued
  const std::function<cl::Event()> reference = [&] {
    order.push_back("reference");
    return fill.launch(-1.0f);
  };
  for (bool ahead : {false, true}) {
    SCOPED_TRACE(ahead ? "frames ahead" : "frame by frame");
    order.clear();
    const std::size_t frames = 4;
    const bench::FrameTimes times = bench::time_frames(
        frames, [](std::size_t) {},
        [&](std::vector<cl::Event>& events, bool timed) {
          order.push_back(timed ? "timed frame" : "frame");
          events.assign(1, fill.launch(float(order.size())));
        },
        ahead, reference);
    ASSERT_EQ(times.device.size(), frames);
    if (ahead) {
      EXPECT_TRUE(times.reference.empty());
      std::vector<std::string> expected(frames + 1, "timed frame");
      expected.front() = "frame";  // the warm-up
      EXPECT_EQ(order, expected);
      continue;
    }
    ASSERT_EQ(times.reference.size(), frames);
    for (double seconds : times.reference) EXPECT_GT(seconds, 0.0);
    std::vector<std::string> expected = {"frame", "reference"};  // the warm-up
    for (std::size_t f = 1; f <= frames; ++f) {
      expected.insert(expected.end(), {"frame", "timed frame", "reference", "reference"});
    }
    EXPECT_EQ(order, expected);
  }
  EXPECT_EQ(fill.first_value(), 5.0f);  // frames ahead: the last frame ran last
}

}  // namespace
}  // namespace finflex
