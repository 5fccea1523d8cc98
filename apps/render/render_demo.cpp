// finflex_render_demo: a few bent fish of two species in a round tank, drawn off-screen
// and written as a PNG (and, with --video, as an animation of swimming fish).
//
//   finflex_render_demo --out tank.png [--width 1280 --height 720] [--frames 20]
//                       [--video swim.mp4 --seconds 4 --fps 30] [--device NAME]
//
// The fish are bent by the OpenCL deformer (ClDeformer, exact bend, Jacobian normals),
// read back to the host and handed to the renderer as FinFlex's structure-of-arrays
// planes; each instance is placed by a transform (body frame -> tank). Run it from the
// repository root (or give --blub / --barramundi). Exit 2 with one line on errors.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "finflex/finflex.hpp"
#include "render/png.hpp"
#include "render/renderer.hpp"
#include "render/video.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr float kPi = 3.14159265f;

double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

// One fish's swimming: it circles the tank (as water in a RAS tank does), beating its
// body from side to side.
struct Swimmer {
  float orbit_radius;  // metres from the tank's axis
  float angle;         // radians around the axis at t = 0
  float height;        // metres above the floor
  float speed;         // metres per second along the orbit
  float beat;          // tail beats per second
  float phase;         // radians
  float pitch;         // radians, nose up
};

struct Species {
  std::string name;
  glm::vec3 albedo;
  float length;  // metres, nose to tail
  finflex::Mesh mesh;
  std::unique_ptr<finflex::RiggedMesh> model;  // the whole-body exact bend
  std::unique_ptr<finflex::ClDeformer> deformer;
  finflex::DeviceBatch batch;
  finflex::DeformedBatch<float> host;
  finflex::render::MeshId mesh_id = 0;
  std::vector<Swimmer> swimmers;
  std::vector<float> m;
  std::vector<glm::mat4> transforms;
};

// Mesh coordinates to the body frame with unit length (METHOD.md (2)).
glm::mat4 body_from_mesh(const finflex::BodyFrame& frame) {
  const glm::mat3 rows = glm::transpose(
      glm::mat3(glm::vec3(frame.axis_x), glm::vec3(frame.axis_y), glm::vec3(frame.axis_z)));
  return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / static_cast<float>(frame.length))) *
         glm::mat4(rows) * glm::translate(glm::mat4(1.0f), -glm::vec3(frame.origin));
}

// Where a swimmer is at time t: body e_x along its path, e_y up, scaled to its length.
glm::mat4 place(const Swimmer& s, float length, float t) {
  const float angle = s.angle + s.speed * t / s.orbit_radius;
  const glm::vec3 position{s.orbit_radius * std::cos(angle), s.height,
                           s.orbit_radius * std::sin(angle)};
  const glm::vec3 along{-std::sin(angle), 0.0f, std::cos(angle)};  // counter-clockwise from above
  const glm::vec3 forward =
      glm::normalize(along * std::cos(s.pitch) + glm::vec3(0.0f, std::sin(s.pitch), 0.0f));
  const glm::vec3 side = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 up = glm::cross(side, forward);
  glm::mat4 world(1.0f);
  world[0] = glm::vec4(forward * length, 0.0f);
  world[1] = glm::vec4(up * length, 0.0f);
  world[2] = glm::vec4(side * length, 0.0f);
  world[3] = glm::vec4(position, 1.0f);
  return world;
}

// A deterministic school: `count` swimmers spread over the tank.
std::vector<Swimmer> school(std::size_t count, unsigned seed, float max_radius) {
  std::vector<Swimmer> swimmers;
  unsigned state = seed;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / static_cast<float>(1u << 24);
  };
  for (std::size_t i = 0; i < count; ++i) {
    Swimmer s{};
    s.orbit_radius = max_radius * std::sqrt(0.08f + 0.92f * next());  // even over the area
    s.angle = 2.0f * kPi * (static_cast<float>(i) + 0.6f * next()) / static_cast<float>(count);
    s.height = 0.2f + 0.6f * next();
    s.speed = 0.25f + 0.15f * next();
    s.beat = 1.2f + 0.8f * next();
    s.phase = 2.0f * kPi * next();
    s.pitch = 0.25f * (next() - 0.5f);
    swimmers.push_back(s);
  }
  return swimmers;
}

void load_species(Species& species, finflex::Context& context, const std::string& path,
                  std::size_t count, unsigned seed) {
  species.mesh = finflex::load_mesh(path);
  species.model = std::make_unique<finflex::RiggedMesh>(finflex::RiggedMesh::single_bend(
      species.mesh, finflex::find_body_frame(species.mesh), finflex::BendMode::kExact));
  species.deformer = std::make_unique<finflex::ClDeformer>(context, *species.model);
  species.batch = species.deformer->allocate(count);
  species.swimmers = school(count, seed, 1.15f);
  species.m.resize(count);
  species.transforms.resize(count);
}

// Bends and places every fish of a species for time t, and reads the batch back.
void pose(Species& species, float t) {
  const auto max_m = static_cast<float>(species.model->rig().parameters[0].limit);
  const finflex::BodyFrame& frame = species.model->rig().components[0].frame;
  for (std::size_t i = 0; i < species.swimmers.size(); ++i) {
    const Swimmer& s = species.swimmers[i];
    species.m[i] = 0.8f * max_m * std::sin(2.0f * kPi * s.beat * t + s.phase);
    species.transforms[i] = place(s, species.length, t) * body_from_mesh(frame);
  }
  finflex::RigParameters values(*species.model, species.m.size());
  values.values() = species.m;
  finflex::ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.normals = finflex::NormalMode::kJacobian;
  job.outputs = &species.batch;
  species.deformer->enqueue(job);
  species.host = species.deformer->read(species.batch);
}

finflex::render::FishDraw draw_of(const Species& species) {
  using finflex::render::StreamLayout;
  using finflex::render::VertexStream;
  const finflex::BatchShape& layout = species.host.shape;
  finflex::render::FishDraw draw;
  draw.mesh = species.mesh_id;
  draw.albedo = species.albedo;
  draw.instance_count = layout.instance_count;
  const StreamLayout planes = StreamLayout::planes(layout.plane_stride);
  draw.positions = VertexStream::from_host(species.host.positions.data(),
                                           species.host.positions.size() * sizeof(float), planes);
  draw.normals = VertexStream::from_host(species.host.normals.data(),
                                         species.host.normals.size() * sizeof(float), planes);
  draw.transforms = species.transforms.data();
  return draw;
}

finflex::render::Camera demo_camera(const std::vector<float>& eye,
                                    const std::vector<float>& look_at) {
  finflex::render::Camera camera;
  camera.position = {eye[0], eye[1], eye[2]};
  camera.target = {look_at[0], look_at[1], look_at[2]};
  camera.vertical_fov_degrees = 42.0f;
  return camera;
}

struct Options {
  std::string out = "render_demo.png";
  std::string video;
  std::string blub = "data/blub/fish.obj";
  std::string barramundi = "data/barramundi/BarramundiFish.gltf";
  std::string device;
  int width = 1280;
  int height = 720;
  int samples = 4;
  int frames = 1;
  float time = 0.4f;
  float seconds = 4.0f;
  int fps = 30;
  std::size_t blub_count = 10;
  std::size_t barramundi_count = 7;
  std::vector<float> eye = {0.0f, 1.75f, 2.5f};
  std::vector<float> look_at = {0.0f, 0.35f, 0.0f};
};

int run(const Options& options) {
  finflex::Context context =
      options.device.empty() ? finflex::Context() : finflex::Context(options.device);
  std::vector<Species> species(2);
  species[0].name = "blub";
  species[0].albedo = {0.80f, 0.36f, 0.10f};  // orange
  species[0].length = 0.32f;
  species[1].name = "barramundi";
  species[1].albedo = {0.55f, 0.58f, 0.56f};  // silver
  species[1].length = 0.45f;
  load_species(species[0], context, options.blub, options.blub_count, 7u);
  load_species(species[1], context, options.barramundi, options.barramundi_count, 11u);

  finflex::render::Renderer renderer({options.width, options.height, options.samples});
  const finflex::render::DeviceInfo& device = renderer.device();
  std::printf("renderer: EGL %s, %s, %s, %dx MSAA\n", device.egl_display.c_str(),
              device.gl_renderer.c_str(), device.gl_version.c_str(), device.samples);
  for (Species& s : species) {
    s.mesh_id = renderer.add_mesh(s.mesh.indices, s.mesh.vertex_count());
    std::printf("%s: %zu fish of %zu vertices, %zu triangles\n", s.name.c_str(), s.swimmers.size(),
                s.mesh.vertex_count(), s.mesh.triangle_count());
  }

  const finflex::render::Scene scene;
  const finflex::render::Camera camera = demo_camera(options.eye, options.look_at);
  const Clock::time_point deform_start = Clock::now();
  for (Species& s : species) pose(s, options.time);
  const double deform_ms = milliseconds_since(deform_start);
  const std::vector<finflex::render::FishDraw> fish = {draw_of(species[0]), draw_of(species[1])};

  std::vector<double> draw_ms;
  std::vector<double> read_ms;
  finflex::render::Image image;
  renderer.render(scene, camera, fish);  // warm-up: shaders compile on first use
  renderer.read_image(image);
  const std::clock_t cpu_start = std::clock();
  for (int frame = 0; frame < options.frames; ++frame) {
    const Clock::time_point start = Clock::now();
    renderer.render(scene, camera, fish);
    renderer.finish();
    draw_ms.push_back(milliseconds_since(start));
    const Clock::time_point read_start = Clock::now();
    renderer.read_image(image);
    read_ms.push_back(milliseconds_since(read_start));
  }
  const double cpu_ms =
      1000.0 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC / options.frames;
  const Clock::time_point png_start = Clock::now();
  finflex::render::write_png(options.out, image);
  const double png_ms = milliseconds_since(png_start);
  std::printf(
      "frame %dx%d, %zu fish: draw %.1f ms, read back %.1f ms (median of %d; CPU time of all "
      "threads %.1f ms a frame), PNG %.1f ms, deform + read of the batches %.1f ms\nwrote %s\n",
      options.width, options.height, options.blub_count + options.barramundi_count, median(draw_ms),
      median(read_ms), options.frames, cpu_ms, png_ms, deform_ms, options.out.c_str());

  if (options.video.empty()) return 0;
  finflex::render::VideoOptions video;
  video.width = options.width;
  video.height = options.height;
  video.fps = options.fps;
  std::unique_ptr<finflex::render::VideoWriter> writer =
      finflex::render::open_video(options.video, video);
  const int frames =
      std::max(1, static_cast<int>(options.seconds * static_cast<float>(options.fps)));
  double pose_total = 0.0;
  double render_total = 0.0;
  double encode_total = 0.0;
  for (int frame = 0; frame < frames; ++frame) {
    const float t = static_cast<float>(frame) / static_cast<float>(options.fps);
    Clock::time_point start = Clock::now();
    for (Species& s : species) pose(s, t);
    pose_total += milliseconds_since(start);
    start = Clock::now();
    renderer.render(scene, camera, {draw_of(species[0]), draw_of(species[1])});
    renderer.read_image(image);
    render_total += milliseconds_since(start);
    start = Clock::now();
    writer->add_frame(image);
    encode_total += milliseconds_since(start);
  }
  const Clock::time_point finish_start = Clock::now();
  writer->finish();
  encode_total += milliseconds_since(finish_start);
  std::printf(
      "video %d frames: deform %.1f, render + read %.1f, encode %.1f ms a frame\nwrote %s\n",
      frames, pose_total / frames, render_total / frames, encode_total / frames,
      writer->path().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Bent fish in a round tank, rendered off-screen to a PNG (and a video)."};
  Options options;
  app.add_option("--out", options.out, "PNG to write");
  app.add_option("--width", options.width, "pixels");
  app.add_option("--height", options.height, "pixels");
  app.add_option("--samples", options.samples, "multisampling, 1..16");
  app.add_option("--frames", options.frames, "times the still frame is drawn, for timing")
      ->check(CLI::PositiveNumber);
  app.add_option("--time", options.time, "seconds into the swim of the still frame");
  app.add_option("--video", options.video, "also write an animation (.mp4 with ffmpeg, .png APNG)");
  app.add_option("--seconds", options.seconds, "length of the animation")
      ->check(CLI::PositiveNumber);
  app.add_option("--fps", options.fps, "frames per second of the animation");
  app.add_option("--blub", options.blub, "mesh of the first species");
  app.add_option("--blub-count", options.blub_count, "fish of the first species")
      ->check(CLI::PositiveNumber);
  app.add_option("--barramundi-count", options.barramundi_count, "fish of the second species")
      ->check(CLI::PositiveNumber);
  app.add_option("--barramundi", options.barramundi, "mesh of the second species");
  app.add_option("--eye", options.eye, "camera position X Y Z, metres (floor centre at 0 0 0)")
      ->expected(3);
  app.add_option("--look-at", options.look_at, "point the camera looks at, X Y Z")->expected(3);
  app.add_option("--device", options.device, "OpenCL device (finflex info lists them)");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(options);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "finflex_render_demo: error: %s\n", error.what());
    return 2;
  }
}
