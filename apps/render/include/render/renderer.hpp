// The off-screen fish-tank renderer: OpenGL 3.3 core through EGL, with no display
// (an EGL device, else Mesa's surfaceless platform, else the default display), so it
// runs on Mesa llvmpipe on a CPU machine and on NVIDIA's EGL driver alike.
//
//   Renderer renderer({1280, 720});                       // throws kNoDevice without EGL
//   MeshId blub = renderer.add_mesh(mesh.indices, mesh.vertex_count());
//   for each frame:
//     FishDraw fish{blub, albedo, n};
//     fish.positions = VertexStream::from_host(batch.positions.data(), bytes,
//                                              StreamLayout::planes(plane_stride));
//     fish.normals = ...; fish.transforms = placements.data();
//     renderer.render(scene, camera, {fish});
//     write_png("frame.png", renderer.read_image());
//
// A frame: the tank and every FishDraw (one instanced draw each; vertex data fetched
// by gl_VertexID and gl_InstanceID from buffer textures) into a multisampled linear
// RGBA16F framebuffer, resolved to a single-sample one, then encoded to sRGB 8-bit
// once. docs/rendering.md describes the passes, the colour pipeline and the cost.
//
// Threads: one thread at a time. Every member that draws or touches a buffer makes the
// renderer's context current on the calling thread first (several renderers may
// share a thread); make_current() does only that, e.g. before OpenCL-GL interop.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/camera.hpp"
#include "render/error.hpp"
#include "render/fish_draw.hpp"
#include "render/id_image.hpp"
#include "render/image.hpp"
#include "render/scene.hpp"

namespace finflex::render {

struct RenderSettings {
  int width = 1280;  // the frame, pixels
  int height = 720;
  int samples = 4;  // multisampling: 1 (off) .. 16; more than the driver has is clamped
  // Most elements one buffer texture may address, below the driver's
  // GL_MAX_TEXTURE_BUFFER_SIZE; 0: the driver's. Larger draws go in runs of instances
  // (see DeviceInfo::texture_buffer_range); a smaller cap exercises that path.
  std::size_t max_buffer_texels = 0;
  // Frames read back asynchronously at once (request_image): 1..16.
  std::size_t frames_in_flight = 3;

  // Throws RenderError (kInvalidArgument) naming "settings.width", ... : sizes 1..16384.
  void validate() const;
};

// What the renderer runs on, for logs and benchmark records.
struct DeviceInfo {
  std::string egl_display;  // how EGL was reached, e.g. "device 0 (software)", "surfaceless"
  std::string gl_vendor;
  std::string gl_renderer;
  std::string gl_version;
  int samples = 0;                    // multisampling in use
  std::size_t max_buffer_texels = 0;  // GL_MAX_TEXTURE_BUFFER_SIZE
  bool texture_buffer_range = false;  // GL 4.3 / ARB_texture_buffer_range: draws of
                                      // any size are split into ranges that fit
  bool device_lists = false;          // GL 4.0 / ARB_draw_indirect: FishDraw::list is drawn
                                      // (glDrawElementsIndirect)
};

// What the context offers for memory and semaphores of another API (Vulkan's, shared
// with OpenCL: finflex/external_outputs.hpp).
struct ExternalSupport {
  bool memory = false;      // GL_EXT_memory_object_fd: buffers in imported memory
  bool semaphores = false;  // GL_EXT_semaphore_fd: GPU-side waits and signals
  std::vector<std::array<std::uint8_t, 16>> device_uuids;  // GL_DEVICE_UUID_EXT
  std::string why_not;  // why memory cannot be imported (empty: it can)
};

using SemaphoreId = std::size_t;

class Renderer {
 public:
  // Creates the EGL display and context (made current) and the framebuffers.
  // Errors: kInvalidArgument (settings); kNoDevice, one line naming what was tried,
  // when no EGL device or display initialises or none gives a GL 3.3 core context;
  // kGraphics when the driver refuses a framebuffer or a shader.
  explicit Renderer(const RenderSettings& settings = {});
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const RenderSettings& settings() const;
  const DeviceInfo& device() const;

  // A mesh (species): triangles counter-clockwise seen from outside, indices below
  // vertex_count. Uploaded once. kInvalidArgument naming "indices" or "indices[k]".
  // `pattern`, empty or one per vertex: the vertex's place on the body, u from the
  // snout (0) to the tail (1) and v from the belly (-1) to the back (1), from which
  // the colour pass paints the species' albedo (countershading, a lateral line and
  // each instance's own shade: docs/rendering.md "Fish appearance"); without it the
  // albedo is flat. kInvalidArgument naming "pattern" for another size or a value
  // that is not finite.
  MeshId add_mesh(const std::vector<std::uint32_t>& indices, std::size_t vertex_count,
                  const std::vector<glm::vec2>& pattern = {});

  // A GL buffer of `bytes` in this renderer's context, for streams that stay on the
  // device (VertexStream::from_buffer). gl_buffer() gives its GL name, e.g. for
  // clCreateFromGLBuffer; write_buffer() copies host bytes into it.
  BufferId create_buffer(std::size_t bytes);
  void write_buffer(BufferId buffer, std::size_t offset, const void* data, std::size_t bytes);
  std::uint32_t gl_buffer(BufferId buffer) const;
  std::size_t buffer_bytes(BufferId buffer) const;

  // ---- External memory (docs/handoff.md "Zero-copy hand-off") ----
  const ExternalSupport& external_support() const;
  // A buffer of `bytes` whose storage is the memory behind `fd` (an opaque fd of a
  // dedicated allocation of `memory_bytes`, e.g. vkGetMemoryFdKHR's), read in place
  // like create_buffer's. GL owns the fd from the call on, also when it fails.
  // Errors: kInvalidArgument naming "fd" (negative) or "bytes" (0, or more than the
  // memory); kGraphics when the driver refuses (no GL_EXT_memory_object_fd, a closed or
  // foreign fd).
  BufferId import_buffer(int fd, std::size_t memory_bytes, std::size_t bytes);
  // A binary semaphore from an opaque fd (GL owns it from then on); kGraphics without
  // GL_EXT_semaphore_fd.
  SemaphoreId import_semaphore(int fd);
  // GPU-side waits and signals, no host wait: GL's later commands wait for the
  // semaphore (which another API has signalled, its signal submitted); or GL signals
  // it after its earlier commands (then flushes, so that another API may wait for it).
  // `buffers`: the buffers the other API writes or reads.
  void wait_semaphore(SemaphoreId semaphore, const std::vector<BufferId>& buffers);
  void signal_semaphore(SemaphoreId semaphore, const std::vector<BufferId>& buffers);

  // Draws a frame. Every draw is validated before anything is drawn: kInvalidArgument
  // naming the field, e.g. "fish[1].normals.layout.vertex_stride" or
  // "fish[0].positions" (too few bytes for its instances), and the value; a device
  // list ("fish[d].list...") where device().device_lists is false, or one whose
  // command or entries do not fit its buffer.
  void render(const Scene& scene, const Camera& camera, const std::vector<FishDraw>& fish);

  // The id pass of the same view: per pixel the FishDraw::ids value of the nearest
  // fish instance (0: none), at one sample per pixel, the tank drawn into the depth
  // only (render/id_image.hpp). Validated as render() does, and every draw with
  // instances needs ids, all > 0 (kInvalidArgument naming "fish[d].ids" or
  // "fish[d].ids[i]"; with a device list, id_count of them, its entries' table). Reuses the
  // streams' uploads of nothing: host streams are copied again, so hand it renderer buffers where
  // both passes run.
  void render_ids(const Scene& scene, const Camera& camera, const std::vector<FishDraw>& fish);
  // The last id pass (waits for the GPU; id passes in flight stay so). kInvalidArgument
  // when none was rendered.
  IdImage read_ids();
  void read_ids(IdImage& out);  // reuses out's storage

  // Waits until the GPU has drawn the frames rendered so far (glFinish).
  void finish();

  // ---- Frames in flight (docs/rendering.md "Frames in flight") ----
  // Starts reading the last frame back (the RGB8 of read_image) into one of
  // settings.frames_in_flight pixel-pack buffers, with a fence: no wait.
  // kInvalidArgument when all of them are pending (take_image first).
  void request_image();
  std::size_t images_pending() const;
  // The oldest requested frame, in request order: waits for that frame's fence only
  // (the GPU may be drawing later ones) and copies it into `out`. kInvalidArgument
  // when none is pending.
  void take_image(Image& out);
  // The GPU time of render()'s passes of the latest frame whose timer query has a
  // result (GL_TIME_ELAPSED, read without waiting; 0 before the first).
  double gpu_draw_seconds();
  // The same for id passes: request_ids after render_ids starts reading its ids and
  // depth back (settings.frames_in_flight at once; kInvalidArgument when none was
  // rendered or all are pending), take_ids waits for the oldest one only.
  void request_ids();
  std::size_t ids_pending() const;
  void take_ids(IdImage& out);
  double gpu_id_seconds();  // render_ids' GPU time, as gpu_draw_seconds()

  // The reference draw of `fish` (docs/rendering.md "The reference draw"): the same
  // triangles, positions as plain vertex attributes, a pass-through shader, one flat
  // colour, one multi-draw per species, into the colour pass's framebuffer (the last
  // frame's image is kept). Validated as render(), and each positions stream must be
  // a renderer buffer of float32 whose instance stride is a multiple of its vertex
  // stride (kInvalidArgument naming "fish[d].positions"), and no device list
  // ("fish[d].list": the reference counts instances on the host). Its GPU time:
  // gpu_reference_seconds(), as gpu_draw_seconds().
  void render_reference(const Scene& scene, const Camera& camera,
                        const std::vector<FishDraw>& fish);
  double gpu_reference_seconds();

  // The last frame as RGB8, sRGB-encoded, rows from the top (waits for the GPU).
  Image read_image();
  void read_image(Image& out);  // reuses out's storage

  // Makes the context current on the calling thread.
  void make_current();

  // The EGL display and context (EGLDisplay, EGLContext), e.g. for an OpenCL context
  // that shares this context's buffers (finflex/gl_outputs.hpp).
  void* egl_display() const;
  void* egl_context() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace finflex::render
