#include "finflex/gl_outputs.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <CL/cl_gl.h>

#include "finflex/error.hpp"

namespace finflex {
namespace {

[[noreturn]] void fail(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, field + ": " + message);
}

bool has_extension(const cl::Device& device, const std::string& name) {
  std::string extensions;
  device.getInfo(CL_DEVICE_EXTENSIONS, &extensions);
  return (" " + extensions + " ").find(" " + name + " ") != std::string::npos;
}

// True when `context` was made with the GL context current on this thread.
bool shares_current_gl_context(const Context& context) {
  const std::vector<cl_context_properties>& properties = context.extra_properties();
  const auto current = reinterpret_cast<cl_context_properties>(eglGetCurrentContext());
  for (std::size_t k = 0; k + 1 < properties.size(); k += 2) {
    if (properties[k] == CL_GL_CONTEXT_KHR && properties[k + 1] == current) return true;
  }
  return false;
}

std::size_t gl_buffer_bytes(std::uint32_t name, const std::string& field) {
  if (!glIsBuffer(name)) fail(field, "GL buffer " + std::to_string(name) + " does not exist");
  GLint64 bytes = 0;
  glBindBuffer(GL_ARRAY_BUFFER, name);
  glGetBufferParameteri64v(GL_ARRAY_BUFFER, GL_BUFFER_SIZE, &bytes);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return static_cast<std::size_t>(std::max<GLint64>(bytes, 0));
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

const char* to_string(GlPath path) { return path == GlPath::kShared ? "shared" : "copy"; }

GlSharingContext make_gl_sharing_context(const std::string& device, void* egl_display,
                                         void* egl_context) {
  GlSharingContext out;
  auto plain = std::make_unique<Context>(device);
  if (!has_extension(plain->device(), "cl_khr_gl_sharing")) {
    out.why_not = "'" + plain->description().device_name + "' has no cl_khr_gl_sharing";
    out.context = std::move(plain);
    return out;
  }
  try {
    out.context = std::make_unique<Context>(
        device, std::vector<cl_context_properties>{
                    CL_GL_CONTEXT_KHR, reinterpret_cast<cl_context_properties>(egl_context),
                    CL_EGL_DISPLAY_KHR, reinterpret_cast<cl_context_properties>(egl_display)});
    out.sharing = true;
  } catch (const Error& e) {
    out.why_not = std::string("the OpenCL platform refused the EGL context: ") + e.what();
    out.context = std::move(plain);
  }
  return out;
}

GlOutputs::GlOutputs(ClDeformer& deformer, std::size_t instances, const OutputLayout& layout,
                     const GlBuffers& buffers)
    : deformer_(deformer), names_(buffers) {
  const std::uint32_t names[4] = {buffers.positions, buffers.normals,
                                  layout.tangents ? buffers.tangents : 0u,
                                  layout.previous_positions ? buffers.previous_positions : 0u};
  const char* fields[4] = {"outputs.positions", "outputs.normals", "outputs.tangents",
                           "outputs.previous_positions"};
  const bool used[4] = {true, true, layout.tangents.has_value(),
                        layout.previous_positions.has_value()};
  for (std::size_t k = 0; k < 4; ++k) {
    if (used[k] && names[k] == 0) fail(fields[k], "no GL buffer given");
  }
  Context& context = deformer.context();
  path_ = shares_current_gl_context(context) ? GlPath::kShared : GlPath::kCopy;
  // One OpenCL buffer per GL buffer: the GL buffer itself (shared) or a device buffer
  // of its size (copy), so attributes interleaved in one GL buffer stay in one.
  cl::Buffer for_name[4];
  for (std::size_t k = 0; k < 4; ++k) {
    if (!used[k]) continue;
    const std::size_t same =
        static_cast<std::size_t>(std::find(names, names + k, names[k]) - names);
    if (same < k) {
      for_name[k] = for_name[same];
      continue;
    }
    const std::size_t bytes = gl_buffer_bytes(names[k], fields[k]);
    cl_int status = CL_SUCCESS;
    if (path_ == GlPath::kShared) {
      cl::BufferGL shared(context.context(), CL_MEM_READ_WRITE, names[k], &status);
      check_cl(status, "clCreateFromGLBuffer");
      shared_.push_back(shared);
      for_name[k] = shared;
    } else {
      // A mirror of the GL buffer, starting from its contents: bytes FinFlex does not
      // write (another attribute of the caller's in an interleaved vertex) keep them.
      std::vector<unsigned char> contents(std::max<std::size_t>(bytes, 1), 0);
      glBindBuffer(GL_ARRAY_BUFFER, names[k]);
      glGetBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), contents.data());
      glBindBuffer(GL_ARRAY_BUFFER, 0);
      for_name[k] = cl::Buffer(context.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                               contents.size(), contents.data(), &status);
      check_cl(status, "clCreateBuffer (GL copy)");
    }
  }
  batch_ = deformer.bind(instances, layout, {for_name[0], for_name[1], for_name[2], for_name[3]});
}

cl::Event GlOutputs::enqueue(const ClJob& job, std::vector<cl::Event>* kernel_events) {
  if (job.outputs != &batch_) {
    throw Error(ErrorCode::kInvalidArgument, "job.outputs",
                "job.outputs: a GlOutputs frame writes its own batch() (set job.outputs to it)");
  }
  if (reading_) {
    throw Error(ErrorCode::kInvalidArgument, "enqueue",
                "enqueue: the batch is being read (begin_reading without end_reading)");
  }
  Context& context = deformer_.context();
  if (path_ == GlPath::kShared) {
    const auto start = std::chrono::steady_clock::now();
    glFinish();  // GL is done with the buffers (no cl_khr_gl_event assumed)
    cl::Event acquired;
    check_cl(context.queue().enqueueAcquireGLObjects(&shared_, job.wait, &acquired),
             "clEnqueueAcquireGLObjects");
    handoff_seconds_ = seconds_since(start);
    ClJob after = job;
    std::vector<cl::Event> wait = {acquired};
    after.wait = &wait;
    const cl::Event done = deformer_.enqueue(after, kernel_events);
    const auto release_start = std::chrono::steady_clock::now();
    std::vector<cl::Event> kernels_done = {done};
    cl::Event released;
    check_cl(context.queue().enqueueReleaseGLObjects(&shared_, &kernels_done, &released),
             "clEnqueueReleaseGLObjects");
    handoff_seconds_ += seconds_since(release_start);
    return released;
  }
  const cl::Event done = deformer_.enqueue(job, kernel_events);
  check_cl(done.wait(), "clWaitForEvents");  // the kernels' time is not the hand-off's
  const auto start = std::chrono::steady_clock::now();
  const cl::Buffer* buffers[4] = {&batch_.positions, &batch_.normals, &batch_.tangents,
                                  &batch_.previous_positions};
  const std::uint32_t names[4] = {
      names_.positions, names_.normals, batch_.outputs.tangents ? names_.tangents : 0u,
      batch_.outputs.previous_positions ? names_.previous_positions : 0u};
  for (std::size_t k = 0; k < 4; ++k) {
    if (names[k] == 0 || std::find(names, names + k, names[k]) != names + k) continue;
    std::size_t bytes = 0;
    buffers[k]->getInfo(CL_MEM_SIZE, &bytes);
    // Mapped rather than read into a staging copy: on a CPU device (PoCL) the map is
    // the buffer itself, so glBufferSubData is the only copy; a GPU driver copies it
    // to the host once either way.
    cl_int status = CL_SUCCESS;
    void* mapped = context.queue().enqueueMapBuffer(*buffers[k], CL_TRUE, CL_MAP_READ, 0, bytes,
                                                    nullptr, nullptr, &status);
    check_cl(status, "clEnqueueMapBuffer (GL copy)");
    glBindBuffer(GL_ARRAY_BUFFER, names[k]);
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), mapped);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    check_cl(context.queue().enqueueUnmapMemObject(*buffers[k], mapped),
             "clEnqueueUnmapMemObject (GL copy)");
  }
  handoff_seconds_ = seconds_since(start);
  return done;
}

void GlOutputs::begin_reading() {
  if (reading_) return;
  if (path_ == GlPath::kShared) {
    glFinish();
    check_cl(deformer_.context().queue().enqueueAcquireGLObjects(&shared_),
             "clEnqueueAcquireGLObjects");
  }
  reading_ = true;
}

void GlOutputs::end_reading() {
  if (!reading_) return;
  reading_ = false;
  if (path_ == GlPath::kShared) {
    cl::Event released;
    check_cl(deformer_.context().queue().enqueueReleaseGLObjects(&shared_, nullptr, &released),
             "clEnqueueReleaseGLObjects");
    check_cl(released.wait(), "clWaitForEvents");
  }
}

}  // namespace finflex
