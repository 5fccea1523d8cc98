// The off-screen renderer (apps/render) on whatever EGL gives: Mesa llvmpipe with no
// display in CI. A straight and a bent fish (the OpenCL deformer's output, read back
// as FinFlex planes) seen from above: both are drawn, lit (not black) and the bent
// one's silhouette moves towards the side it bends to. The stream layouts and sources
// give the same picture; bad draws are refused naming the field.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "finflex/body_frame.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/mesh_io.hpp"
#include "finflex/reference.hpp"
#include "render/refraction.hpp"
#include "render/renderer.hpp"
#include "support/deform.hpp"
#include "support/test_support.hpp"

namespace finflex::render {
namespace {

constexpr int kWidth = 256;
constexpr int kHeight = 192;

// Blub (low resolution) straight (instance 0) and bent (instance 1, m at 0.8 of its
// range: the spine becomes z = m x^2, both ends towards the body's +z side).
struct FishPair {
  Mesh mesh;
  BodyFrame frame;
  DeformedBatch<float> batch;
};

const FishPair& fish_pair() {
  static const FishPair pair = [] {
    FishPair p;
    p.mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
    p.frame = find_body_frame(p.mesh);
    const RiggedMesh model = RiggedMesh::single_bend(p.mesh, p.frame, BendMode::kExact);
    ClDeformer deformer(test::shared_context(), model);
    const auto bend = static_cast<float>(0.8 * model.rig().parameters[0].limit);
    p.batch =
        test::run_on_device(deformer, test::values_of(model, {0.0f, bend}), NormalMode::kJacobian);
    return p;
  }();
  return pair;
}

// World from mesh: the body frame's e_x (head) to world +x, e_y (back) up, e_z to
// world +z; one metre long, at the middle of the water.
glm::mat4 placement(const BodyFrame& frame) {
  glm::mat4 rows(1.0f);
  rows[0] = glm::vec4(frame.axis_x.x, frame.axis_y.x, frame.axis_z.x, 0.0);
  rows[1] = glm::vec4(frame.axis_x.y, frame.axis_y.y, frame.axis_z.y, 0.0);
  rows[2] = glm::vec4(frame.axis_x.z, frame.axis_y.z, frame.axis_z.z, 0.0);
  glm::mat4 world(1.0f);
  world[3] = glm::vec4(0.0f, 0.5f, 0.0f, 1.0f);
  const auto scale = static_cast<float>(1.0 / frame.length);
  return world * glm::mat4(glm::mat3(scale)) * rows *
         glm::translate(glm::mat4(1.0f), -glm::vec3(frame.origin));
}

// Straight down onto the fish, world -z at the top of the image.
Camera top_camera(float height = 1.6f, float vertical_fov_degrees = 50.0f) {
  Camera camera;
  camera.position = {0.0f, height, 0.0f};
  camera.target = {0.0f, 0.5f, 0.0f};
  camera.up = {0.0f, 0.0f, -1.0f};
  camera.vertical_fov_degrees = vertical_fov_degrees;
  return camera;
}

Renderer& renderer() {
  static Renderer shared({kWidth, kHeight, 4});
  return shared;
}

MeshId blub_mesh() {
  static const MeshId id =
      renderer().add_mesh(fish_pair().mesh.indices, fish_pair().mesh.vertex_count());
  return id;
}

// Instance `instance` of the pair as planes straight from the batch (an offset picks it).
FishDraw planes_draw(std::size_t instance) {
  const DeformedBatch<float>& batch = fish_pair().batch;
  StreamLayout layout = StreamLayout::planes(batch.shape.plane_stride);
  layout.offset = instance * layout.instance_stride;
  FishDraw draw;
  draw.mesh = blub_mesh();
  draw.instance_count = 1;
  draw.positions = VertexStream::from_host(batch.positions.data(),
                                           batch.positions.size() * sizeof(float), layout);
  draw.normals =
      VertexStream::from_host(batch.normals.data(), batch.normals.size() * sizeof(float), layout);
  return draw;
}

Image render_fish(const std::vector<FishDraw>& fish, const glm::mat4* transform) {
  std::vector<FishDraw> placed = fish;
  for (FishDraw& draw : placed) draw.transforms = transform;
  renderer().render(Scene{}, top_camera(), placed);
  return renderer().read_image();
}

// Pixels that differ from the empty tank: the fish's silhouette.
struct Silhouette {
  std::vector<bool> inside;
  std::size_t count = 0;
  glm::dvec2 centroid{0.0};
  double mean_brightness = 0.0;  // of the fish's pixels, 0..255
};

Silhouette silhouette(const Image& image, const Image& empty) {
  Silhouette s;
  s.inside.assign(static_cast<std::size_t>(kWidth * kHeight), false);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t* a = image.pixel(x, y);
      const std::uint8_t* b = empty.pixel(x, y);
      int difference = 0;
      for (int c = 0; c < 3; ++c) difference += std::abs(int{a[c]} - int{b[c]});
      if (difference <= 24) continue;
      s.inside[static_cast<std::size_t>(y * kWidth + x)] = true;
      ++s.count;
      s.centroid += glm::dvec2(x, y);
      s.mean_brightness += (a[0] + a[1] + a[2]) / 3.0;
    }
  }
  if (s.count > 0) {
    s.centroid /= static_cast<double>(s.count);
    s.mean_brightness /= static_cast<double>(s.count);
  }
  return s;
}

// The image direction (unit) of the body's +z side, seen by top_camera.
glm::dvec2 lateral_direction() {
  const glm::vec3 centre = project_to_pixel(top_camera(), kWidth, kHeight, {0.0f, 0.5f, 0.0f});
  const glm::vec3 side = project_to_pixel(top_camera(), kWidth, kHeight, {0.0f, 0.5f, 0.3f});
  return glm::normalize(glm::dvec2(side.x - centre.x, side.y - centre.y));
}

TEST(Render, DrawsAStraightAndABentFishThatBendsToItsSide) {
  const glm::mat4 transform = placement(fish_pair().frame);
  const Image empty = render_fish({}, &transform);
  const Image straight = render_fish({planes_draw(0)}, &transform);
  const Image bent = render_fish({planes_draw(1)}, &transform);
  ASSERT_EQ(straight.width, kWidth);
  ASSERT_EQ(straight.rgb.size(), static_cast<std::size_t>(kWidth * kHeight * 3));

  const Silhouette s = silhouette(straight, empty);
  const Silhouette b = silhouette(bent, empty);
  const auto pixels = static_cast<double>(kWidth * kHeight);
  // A one-metre fish seen from 1.1 m covers a good part of the image, not all of it.
  EXPECT_GT(static_cast<double>(s.count), 0.03 * pixels);
  EXPECT_LT(static_cast<double>(s.count), 0.6 * pixels);
  EXPECT_GT(static_cast<double>(b.count), 0.03 * pixels);
  // Lit: neither black nor burnt out.
  EXPECT_GT(s.mean_brightness, 50.0);
  EXPECT_LT(s.mean_brightness, 235.0);
  EXPECT_GT(b.mean_brightness, 50.0);

  // The straight fish lies across the image centre; the bent one's ends move to +z.
  const glm::dvec2 centre(kWidth / 2.0, kHeight / 2.0);
  const glm::dvec2 lateral = lateral_direction();
  EXPECT_LT(std::abs(glm::dot(s.centroid - centre, lateral)), 6.0);
  EXPECT_GT(glm::dot(b.centroid - s.centroid, lateral), 2.0);
  // Pixels the bend adds lie on the +z side of the straight fish's centre line; those
  // it removes, on the -z side.
  std::size_t added_plus = 0;
  std::size_t added_minus = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const auto i = static_cast<std::size_t>(y * kWidth + x);
      if (!b.inside[i] || s.inside[i]) continue;
      const double side = glm::dot(glm::dvec2(x, y) - s.centroid, lateral);
      (side > 0.0 ? added_plus : added_minus) += 1;
    }
  }
  EXPECT_GT(added_plus, 200u);
  EXPECT_GT(added_plus, 4 * added_minus);
}

TEST(Render, APatternPaintsTheBackDarkerThanTheBellyAndEachFishItsOwnShade) {
  // The straight fish seen from above, painted as all back (v = 1), all belly (v = -1)
  // and flat (no pattern); then all back with two ids.
  const FishPair& pair = fish_pair();
  const std::size_t slots = pair.batch.shape.plane_stride;
  const auto mesh_with = [&](float v) {
    return renderer().add_mesh(pair.mesh.indices, slots,
                               std::vector<glm::vec2>(slots, glm::vec2(0.5f, v)));
  };
  const glm::mat4 place = placement(pair.frame);
  const Image empty = render_fish({}, nullptr);
  const auto brightness = [&](MeshId mesh, std::uint32_t id) {
    FishDraw draw = planes_draw(0);
    draw.mesh = mesh;
    draw.ids = &id;
    draw.transforms = &place;
    renderer().render(Scene{}, top_camera(), {draw});
    return silhouette(renderer().read_image(), empty).mean_brightness;
  };
  const MeshId back = mesh_with(1.0f);
  const double flat = brightness(blub_mesh(), 1);
  const double dark = brightness(back, 1);
  const double pale = brightness(mesh_with(-1.0f), 1);
  EXPECT_LT(dark, flat - 10.0);
  EXPECT_GT(pale, flat);
  EXPECT_NE(brightness(back, 1), brightness(back, 2));  // each id its own shade
  EXPECT_EQ(brightness(back, 7), brightness(back, 7));
  try {
    renderer().add_mesh(pair.mesh.indices, slots, std::vector<glm::vec2>(3));
    ADD_FAILURE() << "a pattern of 3 values was accepted";
  } catch (const RenderError& e) {
    EXPECT_EQ(e.field(), "pattern");
  }
}

// The straight fish half a metre under the surface (its middle at (0.3, 0.5, 0.2)) drawn
// with the view rays refracted on the GPU, and drawn straight at the apparent points the
// double-precision oracle gives each vertex: the silhouettes agree.
void expect_refraction_as_the_oracle(const Scene& scene, const Camera& camera) {
  const FishPair& pair = fish_pair();
  const glm::mat4 place =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.0f, 0.2f)) * placement(pair.frame);
  const std::size_t vertices = pair.mesh.vertex_count();
  const std::size_t plane = pair.batch.shape.plane_stride;
  std::vector<float> seen(3 * vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    const glm::dvec3 local(pair.batch.positions[v], pair.batch.positions[plane + v],
                           pair.batch.positions[2 * plane + v]);
    const glm::dvec3 world = glm::dvec3(glm::dmat4(place) * glm::dvec4(local, 1.0));
    const glm::dvec3 apparent = apparent_point(scene, camera, world);
    for (int c = 0; c < 3; ++c) seen[3 * v + std::size_t(c)] = float(apparent[c]);
  }
  // Coverage from the id pass (no shading to tell apart): pixels and their centroid.
  const std::uint32_t id = 1;
  const auto draw = [&](const Scene& look, FishDraw fish) {
    fish.ids = &id;
    renderer().render_ids(look, camera, {fish});
    const IdImage ids = renderer().read_ids();
    Silhouette s;
    s.inside.assign(ids.ids.size(), false);
    for (int y = 0; y < ids.height; ++y) {
      for (int x = 0; x < ids.width; ++x) {
        if (ids.ids[ids.index(x, y)] != id) continue;
        s.inside[ids.index(x, y)] = true;
        ++s.count;
        s.centroid += glm::dvec2(x, y);
      }
    }
    s.centroid /= double(std::max<std::size_t>(s.count, 1));
    return s;
  };
  FishDraw refracted = planes_draw(0);
  refracted.transforms = &place;
  const Silhouette gpu = draw(scene, refracted);
  FishDraw oracle = planes_draw(0);
  oracle.positions = VertexStream::from_host(seen.data(), seen.size() * sizeof(float),
                                             StreamLayout::interleaved(vertices));
  Scene straight = scene;
  straight.view_refraction = ViewRefraction::kNone;
  const Silhouette host = draw(straight, oracle);
  const Silhouette unbent = draw(straight, refracted);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < gpu.inside.size(); ++i) differ += gpu.inside[i] != host.inside[i];
  ASSERT_GT(gpu.count, 200u);
  EXPECT_LT(double(differ), 0.01 * double(gpu.count)) << differ << " of " << gpu.count;
  EXPECT_LT(glm::length(gpu.centroid - host.centroid), 0.05);
  EXPECT_GT(glm::length(gpu.centroid - unbent.centroid), 5.0);  // refraction moves it
  std::printf(
      "refraction at the %s: %zu of %zu pixels differ, centroids %.3f px apart (%.1f px moved)\n",
      to_string(scene.view_refraction), differ, gpu.count,
      glm::length(gpu.centroid - host.centroid), glm::length(gpu.centroid - unbent.centroid));
}

TEST(Render, RefractionPerVertexIsWhereSnellsLawPutsTheFish) {
  // Seen obliquely from above through the surface.
  Camera camera;
  camera.position = {0.0f, 2.2f, 1.6f};
  camera.target = {0.3f, 0.5f, 0.2f};
  Scene scene;
  scene.view_refraction = ViewRefraction::kSurface;
  expect_refraction_as_the_oracle(scene, camera);
}

TEST(Render, RefractionAtACameraPortIsWhereSnellsLawPutsTheFish) {
  // From a camera in the water 0.8 m away behind a flat acrylic port, the fish off its
  // axis (where the port moves it most).
  Camera camera;
  camera.position = {0.1f, 0.45f, 1.0f};
  camera.target = {0.0f, 0.4f, 0.2f};
  camera.near_plane = 0.03f;
  Scene scene;
  scene.view_refraction = ViewRefraction::kPort;
  expect_refraction_as_the_oracle(scene, camera);
}

TEST(Render, PlanesInterleavedHalfAndDeviceBuffersGiveTheSamePicture) {
  const FishPair& pair = fish_pair();
  const glm::mat4 transform = placement(pair.frame);
  const Image reference = render_fish({planes_draw(1)}, &transform);

  const std::size_t vertices = pair.mesh.vertex_count();
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<std::uint16_t> half_normals;
  for (std::size_t v = 0; v < vertices; ++v) {
    for (int c = 0; c < 3; ++c) {
      positions.push_back(pair.batch.positions[pair.batch.shape.index(1, c, v)]);
      normals.push_back(pair.batch.normals[pair.batch.shape.index(1, c, v)]);
      half_normals.push_back(glm::packHalf1x16(normals.back()));
    }
  }
  FishDraw interleaved;
  interleaved.mesh = blub_mesh();
  interleaved.instance_count = 1;
  interleaved.positions = VertexStream::from_host(positions.data(), positions.size() * 4,
                                                  StreamLayout::interleaved(vertices));
  interleaved.normals = VertexStream::from_host(normals.data(), normals.size() * 4,
                                                StreamLayout::interleaved(vertices));
  EXPECT_EQ(render_fish({interleaved}, &transform).rgb, reference.rgb);

  FishDraw device = interleaved;
  const BufferId buffer = renderer().create_buffer(positions.size() * 4);
  renderer().write_buffer(buffer, 0, positions.data(), positions.size() * 4);
  device.positions = VertexStream::from_buffer(buffer, StreamLayout::interleaved(vertices));
  EXPECT_EQ(render_fish({device}, &transform).rgb, reference.rgb);

  FishDraw half = interleaved;
  half.normals =
      VertexStream::from_host(half_normals.data(), half_normals.size() * 2,
                              StreamLayout::interleaved(vertices, ComponentType::kFloat16));
  const Image half_image = render_fish({half}, &transform);
  int largest = 0;
  for (std::size_t i = 0; i < half_image.rgb.size(); ++i) {
    largest = std::max(largest, std::abs(int{half_image.rgb[i]} - int{reference.rgb[i]}));
  }
  EXPECT_LE(largest, 3) << "half normals shade like float ones, within rounding";
}

TEST(Render, ManyInstancesInOneDraw) {
  // The same straight fish 9 times on a 3 x 3 grid, in one draw: 9 separate blobs.
  const FishPair& pair = fish_pair();
  std::vector<glm::mat4> transforms;
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column) {
      const glm::mat4 shift =
          glm::translate(glm::mat4(1.0f), glm::vec3(0.6f * static_cast<float>(column - 1), 0.0f,
                                                    0.5f * static_cast<float>(row - 1)));
      transforms.push_back(shift * glm::mat4(glm::mat3(0.3f)) * placement(pair.frame));
    }
  }
  StreamLayout layout = StreamLayout::planes(pair.batch.shape.plane_stride);
  layout.instance_stride = 0;  // every instance reads instance 0's vertices
  FishDraw draw = planes_draw(0);
  draw.instance_count = transforms.size();
  draw.positions.layout = layout;
  draw.normals.layout = layout;
  draw.transforms = transforms.data();
  renderer().render(Scene{}, top_camera(), {draw});
  const Image many = renderer().read_image();
  const Image empty = render_fish({}, nullptr);
  const Silhouette s = silhouette(many, empty);
  // Each fish at the centre of its cell.
  for (const glm::mat4& t : transforms) {
    const glm::vec3 at = project_to_pixel(top_camera(), kWidth, kHeight, glm::vec3(t[3]));
    const auto i =
        static_cast<std::size_t>(static_cast<int>(at.y) * kWidth + static_cast<int>(at.x));
    EXPECT_TRUE(s.inside[i]) << "no fish at " << at.x << ", " << at.y;
  }
  EXPECT_FALSE(s.inside[static_cast<std::size_t>(2 * kWidth + 2)]);  // a corner stays empty
}

TEST(Render, DrawsSplitIntoRunsGiveTheSamePicture) {
  // Nine instances with their own vertices (straight and bent in turn), in planes; a
  // second renderer whose buffer textures address only a little over two instances
  // draws them in runs, binding each run's range: the picture must not change.
  const FishPair& pair = fish_pair();
  const BatchShape& source = pair.batch.shape;
  const std::size_t count = 9;
  const std::size_t plane = source.plane_stride;
  std::vector<float> positions(count * 3 * plane);
  std::vector<float> normals(count * 3 * plane);
  std::vector<glm::mat4> transforms;
  for (std::size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 3; ++c) {
      const std::size_t from = source.index(i % 2, c, 0);
      std::copy_n(
          pair.batch.positions.begin() + static_cast<long>(from), plane,
          positions.begin() + static_cast<long>((i * 3 + static_cast<std::size_t>(c)) * plane));
      std::copy_n(
          pair.batch.normals.begin() + static_cast<long>(from), plane,
          normals.begin() + static_cast<long>((i * 3 + static_cast<std::size_t>(c)) * plane));
    }
    const auto column = static_cast<float>(i % 3);
    const auto row = static_cast<float>(i / 3);
    transforms.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(0.6f * (column - 1.0f), 0.0f,
                                                                   0.5f * (row - 1.0f))) *
                         glm::mat4(glm::mat3(0.3f)) * placement(pair.frame));
  }
  const auto draw_on = [&](Renderer& target, MeshId mesh) {
    FishDraw draw;
    draw.mesh = mesh;
    draw.instance_count = count;
    draw.positions = VertexStream::from_host(positions.data(), positions.size() * 4,
                                             StreamLayout::planes(plane));
    draw.normals =
        VertexStream::from_host(normals.data(), normals.size() * 4, StreamLayout::planes(plane));
    draw.transforms = transforms.data();
    target.render(Scene{}, top_camera(), {draw});
    return target.read_image();
  };
  const Image whole = draw_on(renderer(), blub_mesh());

  RenderSettings settings{kWidth, kHeight, 4};
  // Runs of two instances (6 planes) and slack: the uploads are read four floats a
  // texel (wide), so 7 planes take 7/4 plane of texels.
  settings.max_buffer_texels = (7 * plane + 3) / 4;
  Renderer split(settings);
  EXPECT_EQ(split.device().max_buffer_texels, (7 * plane + 3) / 4);
  if (!split.device().texture_buffer_range) GTEST_SKIP() << "no glTexBufferRange";
  const MeshId mesh = split.add_mesh(pair.mesh.indices, pair.mesh.vertex_count());
  EXPECT_EQ(draw_on(split, mesh).rgb, whole.rgb);
  // The first renderer still draws after the second one (each makes its context current).
  EXPECT_EQ(draw_on(renderer(), blub_mesh()).rgb, whole.rgb);
}

RenderError error_of(const std::vector<FishDraw>& fish) {
  try {
    renderer().render(Scene{}, top_camera(), fish);
  } catch (const RenderError& error) {
    return error;
  }
  return RenderError(ErrorCode::kGraphics, "none", "no error");
}

TEST(Render, RefusesBadDrawsNamingTheField) {
  FishDraw short_stream = planes_draw(1);
  short_stream.positions.host_bytes =
      short_stream.positions.layout.required_bytes(1, fish_pair().mesh.vertex_count()) - 4;
  RenderError error = error_of({planes_draw(0), short_stream});
  EXPECT_EQ(error.code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(error.field(), "fish[1].positions");

  FishDraw odd_stride = planes_draw(0);
  odd_stride.normals.layout.vertex_stride = 6;
  error = error_of({odd_stride});
  EXPECT_EQ(error.field(), "fish[0].normals.layout.vertex_stride");
  EXPECT_NE(std::string(error.what()).find("6"), std::string::npos);

  FishDraw no_mesh = planes_draw(0);
  no_mesh.mesh = 99;
  EXPECT_EQ(error_of({no_mesh}).field(), "fish[0].mesh");

  FishDraw two_sources = planes_draw(0);
  two_sources.normals.buffer = 0;
  EXPECT_EQ(error_of({two_sources}).field(), "fish[0].normals");

  Camera camera = top_camera();
  camera.up = {0.0f, 1.0f, 0.0f};  // along the view
  try {
    renderer().render(Scene{}, camera, {});
    ADD_FAILURE() << "a camera looking along its up vector was accepted";
  } catch (const RenderError& e) {
    EXPECT_EQ(e.field(), "camera.up");
  }
  EXPECT_THROW(renderer().add_mesh({0, 1, 7}, 3), RenderError);
}

TEST(Render, WithoutAnyEglDeviceTheErrorIsOneLine) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // a fresh process: EGL not loaded yet
  EXPECT_EXIT(
      {
        // GLVND loads no vendor library: no EGL device or display exists.
        setenv("__EGL_VENDOR_LIBRARY_FILENAMES", "/nonexistent/vendor.json", 1);
        try {
          Renderer renderer({64, 64, 1});
        } catch (const RenderError& error) {
          const std::string message = error.what();
          const bool one_line = message.find('\n') == std::string::npos;
          std::fprintf(stderr, "%s\n", message.c_str());
          std::exit(error.code() == ErrorCode::kNoDevice && one_line ? 0 : 1);
        }
        std::exit(3);
      },
      testing::ExitedWithCode(0), "no EGL device or display could be initialised");
}

}  // namespace
}  // namespace finflex::render

namespace finflex::render {
namespace {

// Frames in flight: images requested after each frame and taken later, oldest first,
// are the frames read synchronously; more requests than the ring holds are refused;
// the GPU's draw time is a plausible one.
TEST(Render, FramesInFlightAreTheFramesInTheirOrder) {
  RenderSettings settings{96, 54, 1};
  settings.frames_in_flight = 3;
  Renderer renderer(settings);
  Camera camera;
  std::vector<Image> now;
  for (int k = 0; k < 3; ++k) {
    Scene scene;
    scene.background = glm::vec3(0.1f * float(k + 1), 0.2f, 0.05f * float(k));
    renderer.render(scene, camera, {});
    now.push_back(renderer.read_image());
    renderer.request_image();
  }
  EXPECT_EQ(renderer.images_pending(), 3u);
  EXPECT_THROW(renderer.request_image(), RenderError);
  for (int k = 0; k < 3; ++k) {
    Image later;
    renderer.take_image(later);
    EXPECT_EQ(later.rgb, now[std::size_t(k)].rgb) << "frame " << k;
  }
  EXPECT_NE(now[0].rgb, now[1].rgb);
  EXPECT_EQ(renderer.images_pending(), 0u);
  Image none;
  EXPECT_THROW(renderer.take_image(none), RenderError);
  renderer.finish();
  const double seconds = renderer.gpu_draw_seconds();
  EXPECT_GT(seconds, 0.0);
  EXPECT_LT(seconds, 10.0);
  RenderSettings bad = settings;
  bad.frames_in_flight = 0;
  EXPECT_THROW(bad.validate(), RenderError);
}

}  // namespace
}  // namespace finflex::render

// Draws whose instances the GPU names (FishDraw::list: glDrawElementsIndirect over a
// command and entries in a renderer buffer) give the picture and the ids of the same
// rows drawn from the host; bad lists are refused naming the field. And a hall of
// tanks in rows (Scene::rows): each tank is drawn where its row and column put it.
namespace finflex::render {
namespace lists {

constexpr int kWidth = 160;
constexpr int kHeight = 120;

Renderer& renderer() {
  static Renderer shared({kWidth, kHeight, 1});
  return shared;
}

// Four rows of the low-resolution Blub at rest, in planes, in renderer buffers; row r
// placed at its own spot on a line (its transform).
struct Rows {
  MeshId mesh = 0;
  std::size_t index_count = 0;
  BufferId positions = kNoBuffer;
  BufferId normals = kNoBuffer;
  StreamLayout layout;
  std::vector<glm::mat4> transforms;
};

const Rows& rows() {
  static const Rows out = [] {
    Rows r;
    const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
    const std::size_t v = mesh.vertex_count();
    r.mesh = renderer().add_mesh(mesh.indices, v);
    r.index_count = mesh.indices.size();
    r.layout = StreamLayout::planes(v);
    std::vector<float> positions, normals;
    glm::dvec3 low(1e30), high(-1e30);
    for (const glm::vec3& p : mesh.positions) {
      low = glm::min(low, glm::dvec3(p));
      high = glm::max(high, glm::dvec3(p));
    }
    const double size = glm::length(high - low);
    for (int row = 0; row < 4; ++row) {
      for (int c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < v; ++i) {
          positions.push_back(float((mesh.positions[i][c] - 0.5 * (low[c] + high[c])) / size));
          normals.push_back(c == 1 ? 1.0f : 0.0f);
        }
      }
      r.transforms.push_back(
          glm::translate(glm::mat4(1.0f), glm::vec3(-0.9f + 0.6f * float(row), 0.5f, 0.0f)) *
          glm::mat4(glm::mat3(0.5f)));
    }
    r.positions = renderer().create_buffer(positions.size() * sizeof(float));
    renderer().write_buffer(r.positions, 0, positions.data(), positions.size() * sizeof(float));
    r.normals = renderer().create_buffer(normals.size() * sizeof(float));
    renderer().write_buffer(r.normals, 0, normals.data(), normals.size() * sizeof(float));
    return r;
  }();
  return out;
}

Camera list_camera() { return top_camera(2.2f, 60.0f); }

FishDraw host_draw(std::size_t count, const std::vector<std::uint32_t>& ids) {
  FishDraw draw;
  draw.mesh = rows().mesh;
  draw.instance_count = count;
  draw.positions = VertexStream::from_buffer(rows().positions, rows().layout);
  draw.normals = VertexStream::from_buffer(rows().normals, rows().layout);
  draw.transforms = rows().transforms.data();
  draw.ids = ids.data();
  return draw;
}

// A list buffer: the command at 0, the entries at 32.
BufferId list_buffer(std::uint32_t drawn, const std::vector<std::uint32_t>& entries) {
  std::vector<std::uint32_t> words(8 + entries.size(), 0u);
  words[0] = static_cast<std::uint32_t>(rows().index_count);
  words[1] = drawn;
  std::copy(entries.begin(), entries.end(), words.begin() + 8);
  const BufferId buffer = renderer().create_buffer(words.size() * 4);
  renderer().write_buffer(buffer, 0, words.data(), words.size() * 4);
  return buffer;
}

FishDraw listed_draw(BufferId list, const std::vector<std::uint32_t>& table) {
  FishDraw draw = host_draw(4, table);
  draw.list.buffer = list;
  draw.list.command_offset = 0;
  draw.list.entries_offset = 32;
  draw.id_count = table.size();
  return draw;
}

TEST(DeviceLists, DrawTheRowsAndIdsTheGpuNames) {
  if (!renderer().device().device_lists) GTEST_SKIP() << "no glDrawElementsIndirect";
  const Scene scene;
  // Three of the four rows drawn; their entries index a table of ids.
  const std::vector<std::uint32_t> table{10, 11, 12, 13, 14, 15, 16, 17, 18};
  const std::vector<std::uint32_t> entries{4, 0, 8, 2};
  const BufferId list = list_buffer(3, entries);
  const std::vector<std::uint32_t> host_ids{14, 10, 18};

  renderer().render(scene, list_camera(), {host_draw(3, host_ids)});
  const Image from_host = renderer().read_image();
  renderer().render(scene, list_camera(), {listed_draw(list, table)});
  const Image from_gpu = renderer().read_image();
  EXPECT_EQ(from_gpu.rgb, from_host.rgb);
  renderer().render(scene, list_camera(), {host_draw(4, {1, 2, 3, 4})});
  EXPECT_NE(renderer().read_image().rgb, from_gpu.rgb) << "the fourth row was drawn";

  renderer().render_ids(scene, list_camera(), {host_draw(3, host_ids)});
  const IdImage ids_from_host = renderer().read_ids();
  renderer().render_ids(scene, list_camera(), {listed_draw(list, table)});
  const IdImage ids_from_gpu = renderer().read_ids();
  EXPECT_EQ(ids_from_gpu.ids, ids_from_host.ids);
  std::vector<bool> seen(19, false);
  for (std::uint32_t id : ids_from_gpu.ids) seen.at(id) = true;
  EXPECT_TRUE(seen[14] && seen[10] && seen[18]);
  EXPECT_FALSE(seen[12]);

  // No instances on the GPU's word: the empty tank.
  renderer().render(scene, list_camera(), {});
  const Image empty = renderer().read_image();
  renderer().render(scene, list_camera(), {listed_draw(list_buffer(0, entries), table)});
  EXPECT_EQ(renderer().read_image().rgb, empty.rgb);
}

std::string field_of(const std::vector<FishDraw>& fish, bool ids = false) {
  try {
    if (ids) {
      renderer().render_ids(Scene{}, list_camera(), fish);
    } else {
      renderer().render(Scene{}, list_camera(), fish);
    }
  } catch (const RenderError& error) {
    EXPECT_EQ(error.code(), ErrorCode::kInvalidArgument) << error.what();
    EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos);
    return error.field();
  }
  return "no error";
}

TEST(DeviceLists, BadListsAreRefusedNamingTheField) {
  if (!renderer().device().device_lists) GTEST_SKIP() << "no glDrawElementsIndirect";
  const std::vector<std::uint32_t> table{1, 2, 3, 4};
  const BufferId list = list_buffer(2, {0, 1, 2, 3});
  FishDraw draw = listed_draw(list, table);
  draw.list.buffer = 999;
  EXPECT_EQ(field_of({draw}), "fish[0].list.buffer");
  draw = listed_draw(list, table);
  draw.list.command_offset = 2;
  EXPECT_EQ(field_of({draw}), "fish[0].list.command_offset");
  draw.list.command_offset = 40;  // 20 bytes from 40 pass the buffer's 48
  EXPECT_EQ(field_of({draw}), "fish[0].list.command_offset");
  draw = listed_draw(list, table);
  draw.list.entries_offset = 36;  // 4 rows from 36 pass the end
  EXPECT_EQ(field_of({draw}), "fish[0].list.entries_offset");
  draw = listed_draw(list, table);
  draw.id_count = 0;
  EXPECT_EQ(field_of({draw}, true), "fish[0].id_count");
  try {
    renderer().render_reference(Scene{}, list_camera(), {listed_draw(list, table)});
    ADD_FAILURE() << "the reference draw took a device list";
  } catch (const RenderError& error) {
    EXPECT_EQ(error.field(), "fish[0].list");
  }
}

TEST(TankRows, EachTankStandsWhereItsRowAndColumnPutIt) {
  // Five tanks in rows of three, 2 m apart: 0 1 2 along +x, then 3 4 behind (-z).
  Scene hall;
  hall.tank.radius = 0.8f;
  hall.rows = {5, 3, 2.0f};
  Camera camera;
  camera.position = {2.0f, 12.0f, -1.0f};
  camera.target = {2.0f, 0.0f, -1.0f};
  camera.up = {0.0f, 0.0f, -1.0f};
  camera.vertical_fov_degrees = 40.0f;
  renderer().render(hall, camera, {});
  const Image image = renderer().read_image();
  const auto at = [&](float x, float z) {
    const glm::vec3 p = project_to_pixel(camera, kWidth, kHeight, {x, 0.0f, z});
    const std::uint8_t* rgb = image.pixel(int(p.x), int(p.y));
    return int(rgb[0]) + int(rgb[1]) + int(rgb[2]);
  };
  const int background = at(4.0f, -2.0f);  // where a sixth tank would stand
  for (int t = 0; t < 5; ++t) {
    const float x = 2.0f * float(t % 3), z = -2.0f * float(t / 3);
    EXPECT_GT(at(x, z), background + 20) << "tank " << t << "'s floor";
  }
  EXPECT_LT(at(1.0f, -1.0f), at(0.0f, 0.0f));  // between four tanks: the room

  Scene crowded = hall;
  crowded.rows.spacing = 1.5f;  // less than the diameter
  EXPECT_THROW(
      {
        try {
          renderer().render(crowded, camera, {});
        } catch (const RenderError& e) {
          EXPECT_EQ(e.field(), "scene.rows.spacing");
          throw;
        }
      },
      RenderError);
  crowded.rows = {0, 1, 2.0f};
  try {
    renderer().render(crowded, camera, {});
    ADD_FAILURE() << "no tanks were accepted";
  } catch (const RenderError& e) {
    EXPECT_EQ(e.field(), "scene.rows.count");
  }
}

}  // namespace lists
}  // namespace finflex::render

// The water's image formation (render/water.hpp, docs/rendering.md "Water") against the
// formula integrated here on its own: a grey floor seen straight down through water of
// known optical properties, lit straight from above.
namespace finflex::render {
namespace water {

double srgb_encode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

struct Floor {
  glm::dvec3 absorption;
  glm::dvec3 scattering;
  double depth;
};

// The floor's linear colour: its light (key and sky, both losing Kirk's K_d with depth)
// attenuated over the depth, plus the light the water scatters back up along the way,
// summed over 20,000 steps.
glm::dvec3 expected_colour(const Floor& f, double albedo, double key, double sky, double g) {
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) {
    const double a = f.absorption[c], b = f.scattering[c], attenuation = a + b;
    const double k = std::sqrt(a * a + (0.425 - 0.19) * a * b);  // mu = 1: straight down
    const double lit = albedo * (sky + key) * std::exp(-k * f.depth);
    const double back = (1 - g * g) / (4 * M_PI * std::pow(1 + g, 3.0));  // 180 degrees
    const int steps = 20000;
    double veil = 0.0;
    for (int i = 0; i < steps; ++i) {
      const double s = (i + 0.5) * f.depth / steps;
      const double source = b * (M_PI * back * key + 0.5 * sky) * std::exp(-k * s);
      veil += source * std::exp(-attenuation * s) * f.depth / steps;
    }
    out[c] = lit * std::exp(-attenuation * f.depth) + veil;
  }
  return out;
}

TEST(Water, AGreyFloorSeenThroughItIsTheImageFormationsColour) {
  const double albedo = 0.5, key = 0.6, sky = 0.2;
  for (const Floor& f : {Floor{glm::dvec3(0.0), glm::dvec3(0.0), 1.0},  // no water: dry shading
                         Floor{{0.30, 0.10, 0.40}, {1.0, 1.1, 1.2}, 1.0},
                         Floor{{0.30, 0.10, 0.40}, {1.0, 1.1, 1.2}, 0.5},
                         Floor{{0.26, 0.06, 0.02}, {8.0, 9.0, 10.0}, 1.0}}) {
    Scene scene;
    scene.tank.water_depth = float(f.depth);
    scene.tank.wall_height = float(f.depth) * 1.1f;
    scene.tank.floor_albedo = scene.tank.wall_albedo = glm::vec3(float(albedo));
    scene.water.absorption = glm::vec3(f.absorption);
    scene.water.scattering = glm::vec3(f.scattering);
    scene.lighting.direction_to_light = {0.0f, 1.0f, 0.0f};
    scene.lighting.key_colour = glm::vec3(float(key));
    scene.lighting.sky_ambient = glm::vec3(float(sky));
    scene.lighting.specular = 0.0f;
    Camera camera;  // straight down onto the floor half-way out from the drain
    camera.position = {0.9f, 2.5f, 0.0f};
    camera.target = {0.9f, 0.0f, 0.0f};
    camera.up = {0.0f, 0.0f, -1.0f};
    camera.vertical_fov_degrees = 4.0f;
    renderer().render(scene, camera, {});
    const Image image = renderer().read_image();
    const glm::dvec3 expected =
        expected_colour(f, albedo, key, sky, double(scene.water.phase_asymmetry));
    const std::uint8_t* pixel = image.pixel(kWidth / 2, kHeight / 2);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(double(pixel[c]), 255.0 * srgb_encode(expected[c]), 1.0)
          << "channel " << c << ", depth " << f.depth << ", scattering " << f.scattering[c];
    }
  }
}

TEST(Water, ItsPropertiesAddUpFromWhatItHolds) {
  // Pure water: Pope and Fry's absorption, Morel's scattering (0.0022 at 500 nm).
  const Water pure = water_optics({0.0f, 0.0f});
  EXPECT_NEAR(pure.absorption.r, 0.2644, 1e-6);
  EXPECT_NEAR(pure.absorption.b, 0.0102, 1e-6);
  EXPECT_NEAR(pure.scattering.g, 0.0022 * std::pow(500.0 / 550.0, 4.32), 1e-7);
  // 1 m^-1 of scattering per NTU at 550 nm, as lambda^-1; CDOM at exp(-0.014 (l - 440)).
  const Water murky = water_optics({4.0f, 2.0f});
  EXPECT_NEAR(murky.scattering.g - pure.scattering.g, 4.0, 1e-5);
  EXPECT_NEAR(murky.scattering.b - pure.scattering.b, 4.0 * 550.0 / 465.0, 1e-5);
  EXPECT_NEAR(murky.absorption.b - pure.absorption.b, 2.0 * std::exp(-0.014 * 25.0), 1e-5);
  EXPECT_NEAR(murky.absorption.r - pure.absorption.r, 2.0 * std::exp(-0.014 * 170.0), 1e-5);
  for (const WaterComposition& bad : {WaterComposition{-1.0f, 0.0f}, WaterComposition{0.0f, NAN}}) {
    try {
      water_optics(bad);
      ADD_FAILURE() << "a bad composition was accepted";
    } catch (const RenderError& e) {
      EXPECT_NE(std::string(e.what()).find(bad.turbidity_ntu < 0 ? "water.turbidity_ntu"
                                                                 : "water.dissolved_absorption"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace water
}  // namespace finflex::render
