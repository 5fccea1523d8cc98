#include "render/renderer.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <meshoptimizer.h>

#include "checks.hpp"
#include "egl_context.hpp"
#include "encode_pass.hpp"
#include "fish_pass.hpp"
#include "fish_validation.hpp"
#include "frames_in_flight.hpp"
#include "gl_resources.hpp"
#include "id_targets.hpp"
#include "reference_pass.hpp"
#include "render_targets.hpp"
#include "scene_uniforms.hpp"
#include "tank_pass.hpp"

namespace finflex::render {

using namespace detail;

namespace {

GlLimits query_limits(std::size_t max_buffer_texels) {
  GlLimits limits;
  GLint value = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &value);
  limits.max_buffer_texels = static_cast<std::size_t>(std::max(value, 0));
  if (max_buffer_texels > 0) {
    limits.max_buffer_texels = std::min(limits.max_buffer_texels, max_buffer_texels);
  }
  glGetIntegerv(GL_MAX_SAMPLES, &value);
  limits.max_samples = std::max(value, 1);
  limits.texture_buffer_range =
      epoxy_gl_version() >= 43 || epoxy_has_gl_extension("GL_ARB_texture_buffer_range");
  limits.draw_indirect = epoxy_gl_version() >= 40 || epoxy_has_gl_extension("GL_ARB_draw_indirect");
  if (limits.texture_buffer_range) {
    glGetIntegerv(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &value);
    limits.buffer_offset_alignment = static_cast<std::size_t>(std::max(value, 1));
  }
  return limits;
}

std::string gl_string(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text != nullptr ? text : "";
}

// Depth-tested, back-face-culled counter-clockwise triangles: every pass's state.
void opaque_triangles() {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
}

void require_no_gl_error(const char* during) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", error);
    throw RenderError(ErrorCode::kGraphics, "gl",
                      std::string("GL error ") + code + " during " + during);
  }
}

const RenderSettings& validated(const RenderSettings& settings) {
  settings.validate();
  return settings;
}

}  // namespace

void RenderSettings::validate() const {
  require_in_range("settings.width", width, 1, 16384);
  require_in_range("settings.height", height, 1, 16384);
  require_in_range("settings.samples", samples, 1, 16);
  require_in_range("settings.frames_in_flight",
                   static_cast<int>(std::min<std::size_t>(frames_in_flight, 1000)), 1, 16);
}

struct Renderer::Impl {
  RenderSettings settings;
  EglContext egl;  // first: the GL objects below go before their context
  GlLimits limits;
  DeviceInfo device;
  RenderTargets targets;
  GlBuffer scene_block;
  TankPass tank;
  FishPass fish;
  // The programs that bend the view rays (Scene::view_refraction), made on first use.
  std::unique_ptr<TankPass> tank_refracted;
  std::unique_ptr<FishPass> fish_refracted;
  std::unique_ptr<FishPass> fish_ids_refracted;
  EncodePass encode;
  std::unique_ptr<IdTargets> id_targets;  // the id pass's, made on its first use
  std::unique_ptr<FishPass> fish_ids;
  Camera id_camera;  // the last id pass's, for its depth
  std::vector<MeshResources> meshes;
  std::vector<BufferResource> buffers;
  std::vector<GlSemaphore> semaphores;
  ReadbackRing readback;
  GpuTimer draw_timer;
  GpuTimer id_timer;
  std::unique_ptr<ReferencePass> reference;  // made on its first use
  GpuTimer reference_timer{4};
  ExternalSupport external = query_external_support();

  explicit Impl(const RenderSettings& requested)
      : settings(validated(requested)),
        limits(query_limits(settings.max_buffer_texels)),
        device(describe(egl, limits, std::min(settings.samples, limits.max_samples))),
        targets(settings.width, settings.height, device.samples),
        scene_block(GlBuffer::create()),
        fish(limits, FishOutput::kLitColour),
        readback("take_image", settings.width, settings.height, {PixelPlane{}},
                 settings.frames_in_flight),
        draw_timer(settings.frames_in_flight + 1),
        id_timer(settings.frames_in_flight + 1) {
    glBindBuffer(GL_UNIFORM_BUFFER, scene_block.get());
    glBufferData(GL_UNIFORM_BUFFER, sizeof(SceneBlock), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    require_no_gl_error("set-up");
  }

  // The scene's programs: the refracting ones where it bends the view rays.
  template <typename Pass, typename... Arguments>
  static Pass& made(std::unique_ptr<Pass>& pass, const Arguments&... arguments) {
    if (!pass) pass = std::make_unique<Pass>(arguments...);
    return *pass;
  }
  TankPass& tank_pass(const Scene& scene) {
    return scene.view_refraction != ViewRefraction::kNone ? made(tank_refracted, true) : tank;
  }
  FishPass& colour_pass(const Scene& scene) {
    return scene.view_refraction != ViewRefraction::kNone
               ? made(fish_refracted, limits, FishOutput::kLitColour, true)
               : fish;
  }
  FishPass& id_pass(const Scene& scene) {
    return scene.view_refraction != ViewRefraction::kNone
               ? made(fish_ids_refracted, limits, FishOutput::kIds, true)
               : *fish_ids;
  }

  // Every pass's start: the context current, its inputs checked.
  void validate(const Scene& scene, const Camera& camera, const std::vector<FishDraw>& draws) {
    egl.make_current();
    scene.validate();
    camera.validate();
    validate_fish(draws, meshes, buffers, limits.draw_indirect);
  }

  // glWaitSemaphoreEXT, or glSignalSemaphoreEXT and a flush (another API's wait needs
  // the signal submitted), over `ids`' buffers.
  void semaphore_operation(SemaphoreId semaphore, const std::vector<BufferId>& ids, bool signal) {
    egl.make_current();
    if (semaphore >= semaphores.size()) invalid("semaphore", std::to_string(semaphore));
    std::vector<GLuint> names;
    for (BufferId b : ids) names.push_back(buffer(b).buffer.get());
    const auto call = signal ? glSignalSemaphoreEXT : glWaitSemaphoreEXT;
    call(semaphores[semaphore].get(), static_cast<GLuint>(names.size()), names.data(), 0, nullptr,
         nullptr);
    if (signal) glFlush();
    require_no_gl_error(signal ? "signal_semaphore" : "wait_semaphore");
  }

  // GL objects are deleted in the context they belong to, whichever is current now.
  ~Impl() { egl.try_make_current(); }

  // The scene's uniform block (lights, tank, camera at the frame's aspect), bound at 0.
  void upload_scene_block(const Scene& scene, const Camera& camera) {
    const float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
    const SceneBlock block = make_scene_block(scene, camera, aspect);
    glBindBuffer(GL_UNIFORM_BUFFER, scene_block.get());
    glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof block, &block);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, scene_block.get());
  }

  static DeviceInfo describe(const EglContext& egl, const GlLimits& limits, int samples) {
    DeviceInfo info;
    info.egl_display = egl.description();
    info.gl_vendor = gl_string(GL_VENDOR);
    info.gl_renderer = gl_string(GL_RENDERER);
    info.gl_version = gl_string(GL_VERSION);
    info.samples = samples;
    info.max_buffer_texels = limits.max_buffer_texels;
    info.texture_buffer_range = limits.texture_buffer_range;
    info.device_lists = limits.draw_indirect;
    return info;
  }

  const BufferResource& buffer(BufferId id) const {
    if (id >= buffers.size()) {
      invalid("buffer", std::to_string(id) + " is not a buffer of this renderer");
    }
    return buffers[id];
  }
};

Renderer::Renderer(const RenderSettings& settings) : impl_(std::make_unique<Impl>(settings)) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

const RenderSettings& Renderer::settings() const { return impl_->settings; }
const DeviceInfo& Renderer::device() const { return impl_->device; }

MeshId Renderer::add_mesh(const std::vector<std::uint32_t>& indices, std::size_t vertex_count,
                          const std::vector<glm::vec2>& pattern) {
  impl_->egl.make_current();
  if (indices.empty() || indices.size() % 3 != 0) {
    invalid("indices", std::to_string(indices.size()) + " indices: not a positive multiple of 3");
  }
  if (vertex_count == 0) invalid("vertex_count", "0");
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (indices[k] >= vertex_count) {
      invalid("indices[" + std::to_string(k) + "]", std::to_string(indices[k]) +
                                                        " is not below the vertex count " +
                                                        std::to_string(vertex_count));
    }
  }
  if (!pattern.empty() && pattern.size() != vertex_count) {
    invalid("pattern", std::to_string(pattern.size()) + " values for " +
                           std::to_string(vertex_count) + " vertices");
  }
  for (std::size_t k = 0; k < pattern.size(); ++k) {
    if (!std::isfinite(pattern[k].x) || !std::isfinite(pattern[k].y)) {
      invalid("pattern[" + std::to_string(k) + "]", "is not finite");
    }
  }
  // The same triangles in the order that reuses transformed vertices best
  // (meshoptimizer's vertex cache optimisation: 1.3 vertex shader runs per vertex for the
  // bundled Blub instead of 2.6-3.0 in its file's order; docs/rendering.md "How the
  // vertex data is consumed").
  std::vector<std::uint32_t> ordered(indices.size());
  meshopt_optimizeVertexCache(ordered.data(), indices.data(), indices.size(), vertex_count);
  MeshResources mesh;
  mesh.vertex_array = GlVertexArray::create();
  mesh.indices = GlBuffer::create();
  mesh.index_count = static_cast<GLsizei>(ordered.size());
  mesh.vertex_count = vertex_count;
  glBindVertexArray(mesh.vertex_array.get());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.indices.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(ordered.size() * sizeof(std::uint32_t)), ordered.data(),
               GL_STATIC_DRAW);
  if (!pattern.empty()) {
    mesh.pattern = GlBuffer::create();
    mesh.patterned = true;
    glBindBuffer(GL_ARRAY_BUFFER, mesh.pattern.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(pattern.size() * sizeof(glm::vec2)),
                 pattern.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(kPatternLocation);
    glVertexAttribPointer(kPatternLocation, 2, GL_FLOAT, GL_FALSE, sizeof(glm::vec2), nullptr);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
  glBindVertexArray(0);
  require_no_gl_error("add_mesh");
  impl_->meshes.push_back(std::move(mesh));
  return impl_->meshes.size() - 1;
}

BufferId Renderer::create_buffer(std::size_t bytes) {
  impl_->egl.make_current();
  if (bytes == 0) invalid("bytes", "0");
  BufferResource resource{GlMemoryObject(), GlBuffer::create(), bytes};
  glBindBuffer(GL_COPY_WRITE_BUFFER, resource.buffer.get());
  glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  require_no_gl_error("create_buffer");
  impl_->buffers.push_back(std::move(resource));
  return impl_->buffers.size() - 1;
}

const ExternalSupport& Renderer::external_support() const { return impl_->external; }

BufferId Renderer::import_buffer(int fd, std::size_t memory_bytes, std::size_t bytes) {
  impl_->egl.make_current();
  if (!impl_->external.memory && fd >= 0) {
    close(fd);
    throw RenderError(ErrorCode::kGraphics, "gl", "import_buffer: " + impl_->external.why_not);
  }
  ImportedBuffer imported = detail::import_buffer(fd, memory_bytes, bytes);
  impl_->buffers.push_back({std::move(imported.memory), std::move(imported.buffer), bytes});
  return impl_->buffers.size() - 1;
}

SemaphoreId Renderer::import_semaphore(int fd) {
  impl_->egl.make_current();
  if (!impl_->external.semaphores) {
    if (fd >= 0) close(fd);
    throw RenderError(ErrorCode::kGraphics, "gl",
                      "import_semaphore: OpenGL has no GL_EXT_semaphore_fd");
  }
  impl_->semaphores.push_back(detail::import_semaphore(fd));
  return impl_->semaphores.size() - 1;
}

void Renderer::wait_semaphore(SemaphoreId semaphore, const std::vector<BufferId>& buffers) {
  impl_->semaphore_operation(semaphore, buffers, false);
}

void Renderer::signal_semaphore(SemaphoreId semaphore, const std::vector<BufferId>& buffers) {
  impl_->semaphore_operation(semaphore, buffers, true);
}

void Renderer::write_buffer(BufferId buffer, std::size_t offset, const void* data,
                            std::size_t bytes) {
  impl_->egl.make_current();
  const BufferResource& resource = impl_->buffer(buffer);
  if (offset > resource.bytes || bytes > resource.bytes - offset) {
    invalid("bytes", std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                         " do not fit the buffer's " + std::to_string(resource.bytes));
  }
  if (bytes == 0) return;
  if (data == nullptr) invalid("data", "null");
  glBindBuffer(GL_COPY_WRITE_BUFFER, resource.buffer.get());
  glBufferSubData(GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(offset),
                  static_cast<GLsizeiptr>(bytes), data);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

std::uint32_t Renderer::gl_buffer(BufferId buffer) const {
  return impl_->buffer(buffer).buffer.get();
}

std::size_t Renderer::buffer_bytes(BufferId buffer) const { return impl_->buffer(buffer).bytes; }

void Renderer::render(const Scene& scene, const Camera& camera, const std::vector<FishDraw>& fish) {
  impl_->validate(scene, camera, fish);
  Impl& r = *impl_;

  r.upload_scene_block(scene, camera);

  r.draw_timer.begin();
  r.targets.bind_scene();
  glClearColor(scene.background.r, scene.background.g, scene.background.b, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  opaque_triangles();
  r.tank_pass(scene).draw(scene.tank, scene.rows);
  r.colour_pass(scene).draw(fish, r.meshes, r.buffers);

  r.targets.resolve();
  r.encode.draw(r.targets);
  r.draw_timer.end();
  require_no_gl_error("render");
}

void Renderer::render_ids(const Scene& scene, const Camera& camera,
                          const std::vector<FishDraw>& fish) {
  impl_->validate(scene, camera, fish);
  validate_ids(fish);
  Impl& r = *impl_;
  if (!r.id_targets) {
    r.id_targets = std::make_unique<IdTargets>(r.settings.width, r.settings.height,
                                               r.settings.frames_in_flight);
    r.fish_ids = std::make_unique<FishPass>(r.limits, FishOutput::kIds);
  }
  r.upload_scene_block(scene, camera);

  r.id_timer.begin();
  r.id_targets->bind_and_clear();
  opaque_triangles();
  glDrawBuffer(GL_NONE);  // the tank hides what is behind it, and writes no id
  r.tank_pass(scene).draw(scene.tank, scene.rows);
  glDrawBuffer(GL_COLOR_ATTACHMENT0);
  r.id_pass(scene).draw(fish, r.meshes, r.buffers);
  r.id_timer.end();
  r.id_camera = camera;
  require_no_gl_error("render_ids");
}

void Renderer::read_ids(IdImage& out) {
  impl_->egl.make_current();
  Impl& r = *impl_;
  if (!r.id_targets) invalid("read_ids", "no id pass was rendered");
  r.id_targets->read(out, r.id_camera.near_plane, r.id_camera.far_plane);
  require_no_gl_error("read_ids");
}

void Renderer::request_ids() {
  impl_->egl.make_current();
  Impl& r = *impl_;
  if (!r.id_targets) invalid("request_ids", "no id pass was rendered");
  if (r.id_targets->pending() == r.id_targets->in_flight()) {
    invalid("request_ids", std::to_string(r.id_targets->in_flight()) +
                               " id passes are in flight already (take_ids first)");
  }
  r.id_targets->request(r.id_camera.near_plane, r.id_camera.far_plane);
  require_no_gl_error("request_ids");
}

std::size_t Renderer::ids_pending() const {
  return impl_->id_targets ? impl_->id_targets->pending() : 0;
}

void Renderer::take_ids(IdImage& out) {
  impl_->egl.make_current();
  Impl& r = *impl_;
  if (!r.id_targets) invalid("take_ids", "no id pass was requested");
  r.id_targets->take(out);
  require_no_gl_error("take_ids");
}

double Renderer::gpu_id_seconds() {
  impl_->egl.make_current();
  return impl_->id_timer.latest_seconds();
}

IdImage Renderer::read_ids() {
  IdImage image;
  read_ids(image);
  return image;
}

void Renderer::finish() {
  impl_->egl.make_current();
  glFinish();
}

void Renderer::read_image(Image& out) {
  impl_->egl.make_current();
  Impl& r = *impl_;
  out.width = r.settings.width;
  out.height = r.settings.height;
  out.rgb.resize(out.row_bytes() * static_cast<std::size_t>(out.height));
  r.targets.bind_output_for_reading();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, out.width, out.height, GL_RGB, GL_UNSIGNED_BYTE, out.rgb.data());
  require_no_gl_error("read_image");
}

void Renderer::request_image() {
  impl_->egl.make_current();
  Impl& r = *impl_;
  if (r.readback.pending() == r.readback.depth()) {
    invalid("request_image", std::to_string(r.readback.depth()) +
                                 " frames are in flight already (take_image first)");
  }
  r.targets.bind_output_for_reading();
  r.readback.request();
  require_no_gl_error("request_image");
}

std::size_t Renderer::images_pending() const { return impl_->readback.pending(); }

void Renderer::take_image(Image& out) {
  impl_->egl.make_current();
  Impl& r = *impl_;
  r.readback.take([&](const std::vector<const void*>& planes) {
    out.width = r.settings.width;
    out.height = r.settings.height;
    const std::size_t bytes = out.row_bytes() * static_cast<std::size_t>(out.height);
    const auto* rgb = static_cast<const std::uint8_t*>(planes[0]);
    out.rgb.assign(rgb, rgb + bytes);  // rows from the top, as the encode pass wrote them
  });
  require_no_gl_error("take_image");
}

void Renderer::render_reference(const Scene& scene, const Camera& camera,
                                const std::vector<FishDraw>& fish) {
  impl_->validate(scene, camera, fish);
  ReferencePass::validate(fish);
  Impl& r = *impl_;
  if (!r.reference) r.reference = std::make_unique<ReferencePass>();
  r.upload_scene_block(scene, camera);
  r.reference_timer.begin();
  r.targets.bind_scene();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  opaque_triangles();
  r.reference->draw(fish, r.meshes, r.buffers);
  r.reference_timer.end();
  require_no_gl_error("render_reference");
}

double Renderer::gpu_reference_seconds() {
  impl_->egl.make_current();
  return impl_->reference_timer.latest_seconds();
}

double Renderer::gpu_draw_seconds() {
  impl_->egl.make_current();
  return impl_->draw_timer.latest_seconds();
}

Image Renderer::read_image() {
  Image image;
  read_image(image);
  return image;
}

void Renderer::make_current() { impl_->egl.make_current(); }
void* Renderer::egl_display() const { return impl_->egl.display(); }
void* Renderer::egl_context() const { return impl_->egl.context(); }

}  // namespace finflex::render
