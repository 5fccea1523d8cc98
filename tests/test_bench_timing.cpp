// The benchmarks' frame loop (bench/support/timing.hpp): one record per timed frame,
// each holding that frame's own kernels, whether each frame is waited for before the
// next is enqueued or the frames run ahead of the device.
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

}  // namespace
}  // namespace finflex
