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

const char* kFill = R"(
__kernel void fill(__global float* out, const float value) {
  out[get_global_id(0)] = value;
}
)";

TEST(BenchTiming, EachFrameRecordsItsOwnKernelsWhetherOrNotFramesRunAhead) {
  Context& context = test::shared_context();
  cl::Program program(context.context(), kFill);
  ASSERT_EQ(program.build(), CL_SUCCESS);
  cl::Kernel kernel(program, "fill");
  cl::Buffer buffer(context.context(), CL_MEM_READ_WRITE, 4096 * sizeof(float));
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
            cl::Event done;
            kernel.setArg(0, buffer);
            kernel.setArg(1, float(enqueued));
            ASSERT_EQ(context.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(4096),
                                                           cl::NDRange(64), nullptr, &done),
                      CL_SUCCESS);
            events.push_back(done);
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
  std::vector<float> last(4096);
  context.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, last.size() * sizeof(float), last.data());
  EXPECT_EQ(last.front(), 6.0f);  // every frame ran, the last one last
}

// A reference kernel runs after every frame waited for (the warm-up's too) and is
// timed on its own; with frames ahead it does not run.
TEST(BenchTiming, AReferenceKernelRunsAfterEveryFrameWaitedFor) {
  Context& context = test::shared_context();
  cl::Program program(context.context(), kFill);
  ASSERT_EQ(program.build(), CL_SUCCESS);
  cl::Kernel kernel(program, "fill");
  cl::Buffer buffer(context.context(), CL_MEM_READ_WRITE, 4096 * sizeof(float));
  std::vector<std::string> order;  // "frame" or "reference", as enqueued
  auto launch = [&](float value) {
    cl::Event done;
    kernel.setArg(0, buffer);
    kernel.setArg(1, value);
    EXPECT_EQ(context.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(4096),
                                                   cl::NDRange(64), nullptr, &done),
              CL_SUCCESS);
    return done;
  };
  const std::function<cl::Event()> reference = [&] {
    order.push_back("reference");
    return launch(-1.0f);
  };
  for (bool ahead : {false, true}) {
    SCOPED_TRACE(ahead ? "frames ahead" : "frame by frame");
    order.clear();
    const std::size_t frames = 4;
    const bench::FrameTimes times = bench::time_frames(
        frames, [](std::size_t) {},
        [&](std::vector<cl::Event>& events) {
          order.push_back("frame");
          events.assign(1, launch(float(order.size())));
        },
        ahead, reference);
    ASSERT_EQ(times.device.size(), frames);
    if (ahead) {
      EXPECT_TRUE(times.reference.empty());
      EXPECT_EQ(order, std::vector<std::string>(frames + 1, "frame"));
      continue;
    }
    ASSERT_EQ(times.reference.size(), frames);
    for (double seconds : times.reference) EXPECT_GT(seconds, 0.0);
    std::vector<std::string> expected;
    for (std::size_t f = 0; f <= frames; ++f)
      expected.insert(expected.end(), {"frame", "reference"});
    EXPECT_EQ(order, expected);
  }
  std::vector<float> last(4096);
  context.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, last.size() * sizeof(float), last.data());
  EXPECT_EQ(last.front(), 5.0f);  // frames ahead: the last frame ran last
}

}  // namespace
}  // namespace finflex
