// Outputs straight into OpenGL buffer objects (library FinFlex::gl, built with the
// project; it needs libepoxy and an EGL context of the caller's, current on the
// calling thread).
//
// Two paths, chosen once and reported:
//  - kShared: the OpenCL context shares the GL context (cl_khr_gl_sharing with an EGL
//    display, make_gl_sharing_context); the kernels write into the GL buffers. Each
//    frame: glFinish (GL is done with the buffers; the spec asks for it without
//    cl_khr_gl_event), acquire, the kernels, release; GL may draw once the returned
//    release event is complete (clWaitForEvents, or a glFinish-free wait of the
//    caller's choosing). No clFinish.
//  - kCopy: anything else (PoCL has no GL sharing): the kernels write a device mirror
//    of each GL buffer (made from its contents, so bytes FinFlex does not write keep
//    the values they had then), then the frame is read back (blocking) and uploaded
//    whole with glBufferSubData.
//
//   finflex::render::Renderer renderer;                                 // EGL, current
//   auto context = finflex::make_gl_sharing_context("", renderer.egl_display(),
//                                                   renderer.egl_context());
//   finflex::ClDeformer deformer(*context.context, fish);
//   finflex::GlOutputs outputs(deformer, 1000, layout, {positions_name, normals_name});
//   job.outputs = &outputs.batch();
//   cl::Event ready = outputs.enqueue(job);   // then draw from the GL buffers
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <CL/opencl.hpp>

#include "finflex/cl_deformer.hpp"
#include "finflex/context.hpp"
#include "finflex/output_layout.hpp"

namespace finflex {

// An OpenCL context for `device` sharing the EGL context's buffers where the platform
// offers it, else a plain one; `sharing` says which and `why_not` why not.
struct GlSharingContext {
  std::unique_ptr<Context> context;
  bool sharing = false;
  std::string why_not;
};
GlSharingContext make_gl_sharing_context(const std::string& device, void* egl_display,
                                         void* egl_context);

enum class GlPath { kShared, kCopy };
const char* to_string(GlPath path);

// GL buffer names (0: none) of each attribute; one name may hold several (interleaved).
struct GlBuffers {
  std::uint32_t positions = 0;
  std::uint32_t normals = 0;
  std::uint32_t tangents = 0;
  std::uint32_t previous_positions = 0;
};

class GlOutputs {
 public:
  // Checks the layout against the GL buffers' sizes (glGetBufferParameteriv) as
  // ClDeformer::bind does, naming "outputs.<attribute>"; shares them when the
  // deformer's context shares the current GL context, else allocates device buffers.
  GlOutputs(ClDeformer& deformer, std::size_t instances, const OutputLayout& layout,
            const GlBuffers& buffers);

  GlPath path() const { return path_; }
  DeviceBatch& batch() { return batch_; }

  // Enqueues `job` (its outputs must be batch()) into the GL buffers as the path says.
  // Returns the event after which GL may read them (kCopy: complete on return).
  // `kernel_events` as ClDeformer::enqueue.
  cl::Event enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events = nullptr);

  // Host time of the last enqueue's hand-off: acquire and release (kShared), or the
  // read-back and glBufferSubData (kCopy), in seconds.
  double last_handoff_seconds() const { return handoff_seconds_; }

 private:
  ClDeformer& deformer_;
  GlPath path_ = GlPath::kCopy;
  GlBuffers names_;
  DeviceBatch batch_;
  std::vector<cl::Memory> shared_;  // kShared: the GL buffers as OpenCL memory objects
  std::vector<unsigned char> staging_;
  double handoff_seconds_ = 0.0;
};

}  // namespace finflex
