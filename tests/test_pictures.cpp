// Pictures of the swim (apps/pictures): the deformation writes the renderer's GL
// buffers through GlOutputs (shared with OpenCL, or copied on PoCL), which hold and
// draw exactly what the engine computes without GL; the id pass covers the fish's silhouette in the
// colour image with the tank's fish ids; masks become COCO's run lengths (checked by hand here and
// against pycocotools by tests/python/check_coco.py); the landmarks are the snout's tip and the
// tail's fork; every camera view frames the whole tank.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "coco_dataset.hpp"
#include "instance_masks.hpp"
#include "landmarks.hpp"
#include "lens.hpp"
#include "support/test_support.hpp"
#include "support/throws_error.hpp"
#include "swim_scene.hpp"
#include "tank_pictures.hpp"
#include "tank_view.hpp"
#include "yolo_labels.hpp"

namespace finflex::pictures {
namespace {

// 4 x 3 ids, rows from the top:   0 1 1 0 / 0 1 2 2 / 0 0 2 0
render::IdImage small_ids() {
  render::IdImage image;
  image.width = 4;
  image.height = 3;
  image.ids = {0, 1, 1, 0, 0, 1, 2, 2, 0, 0, 2, 0};
  image.depth.assign(12, 1.0f);
  return image;
}

TEST(Masks, RunLengthsAreCocosColumnMajorCounts) {
  // Column-major: 0 0 0 | 1 1 0 | 1 2 2 | 0 2 0.
  const std::vector<InstanceMask> masks = instance_masks(small_ids());
  ASSERT_EQ(masks.size(), 2u);
  EXPECT_EQ(masks[0].id, 1u);
  EXPECT_EQ(masks[0].counts, (std::vector<std::uint32_t>{3, 2, 1, 1, 5}));
  EXPECT_EQ(masks[0].area, 3u);
  EXPECT_EQ(std::vector<int>({masks[0].x_min, masks[0].y_min, masks[0].x_max, masks[0].y_max}),
            std::vector<int>({1, 0, 2, 1}));
  EXPECT_EQ(masks[1].id, 2u);
  EXPECT_EQ(masks[1].counts, (std::vector<std::uint32_t>{7, 2, 1, 1, 1}));
  EXPECT_EQ(std::vector<int>({masks[1].x_min, masks[1].y_min, masks[1].x_max, masks[1].y_max}),
            std::vector<int>({2, 1, 3, 2}));
  // pycocotools' string: 3, 2, 1, then 1 - 2 = -1 (31 with the sign's bits: 'O'), 5 - 1 = 4.
  EXPECT_EQ(compress_counts(masks[0].counts), "321O4");
  // Counts of 32 and more take two groups, the first flagged with 0x20.
  EXPECT_EQ(compress_counts({40}), std::string({char(48 + (40 & 0x1f) + 0x20), char(48 + 1)}));
  // An empty image has no instances.
  render::IdImage empty = small_ids();
  std::fill(empty.ids.begin(), empty.ids.end(), 0u);
  EXPECT_TRUE(instance_masks(empty).empty());
}

double shoelace(const std::vector<glm::dvec2>& polygon) {
  double twice = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const glm::dvec2 a = polygon[k], b = polygon[(k + 1) % polygon.size()];
    twice += a.x * b.y - a.y * b.x;
  }
  return 0.5 * twice;  // > 0: clockwise on the image (y down)
}

render::IdImage ids_from_rows(const std::vector<std::string>& rows) {
  render::IdImage image;
  image.height = int(rows.size());
  image.width = int(rows[0].size());
  for (const std::string& row : rows) {
    for (char c : row) image.ids.push_back(c == '.' ? 0u : std::uint32_t(c - '0'));
  }
  image.depth.assign(image.ids.size(), 1.0f);
  return image;
}

TEST(YoloLabels, OutlinesFollowThePixelEdgesAndJoinTheirParts) {
  // Fish 1: an L and, apart from it, a single pixel touching it only at a corner
  // (4-connectivity: two parts); fish 2: a ring around a hole.
  const render::IdImage ids = ids_from_rows({"11.222.",  //
                                             "1.12.2.",  //
                                             "...222."});
  const std::vector<InstanceMask> masks = instance_masks(ids);
  ASSERT_EQ(masks.size(), 2u);
  const std::vector<glm::dvec2> one = mask_outline(ids, masks[0]);
  // The L (3 pixels) and the pixel at (2, 1): corners only, every edge axis-aligned,
  // the two parts joined there and back (the bridge adds no area).
  EXPECT_DOUBLE_EQ(shoelace(one), 4.0);
  for (const glm::dvec2& p : one) EXPECT_EQ(p, glm::round(p));  // pixel corners
  EXPECT_EQ(one.front(), glm::dvec2(0.0, 0.0));
  // The ring's outline is its outer boundary, the square around it: its hole counts
  // (9 = 8 + 1).
  const std::vector<glm::dvec2> ring = mask_outline(ids, masks[1]);
  EXPECT_DOUBLE_EQ(shoelace(ring), 9.0);
  EXPECT_EQ(ring, (std::vector<glm::dvec2>{{3, 0}, {6, 0}, {6, 3}, {3, 3}}));

  // Lines: class, box (centre, size) normalised; pose adds the keypoints, 0 0 0 outside.
  const std::string detect = yolo_line(YoloTask::kDetect, 1, masks[0], one, {}, 7, 3);
  EXPECT_EQ(detect, "1 0.214286 0.333333 0.428571 0.666667");
  const std::string pose =
      yolo_line(YoloTask::kPose, 0, masks[0], one, {{{0.5, 1.5, 2.0}, {0.0, 0.0, 0.0}}}, 7, 3);
  EXPECT_EQ(pose, "0 0.214286 0.333333 0.428571 0.666667 0.071429 0.500000 2 0.000000 0.000000 0");
  const std::string segment = yolo_line(YoloTask::kSegment, 0, masks[1], ring, {}, 7, 3);
  EXPECT_EQ(segment.substr(0, 20), "0 0.428571 0.000000 ");
  const std::string yaml =
      yolo_dataset_yaml(YoloTask::kPose, {"blub", "barramundi"}, {"snout", "tail_fork"}, {0, 1});
  EXPECT_NE(yaml.find("names:\n  0: blub\n  1: barramundi\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("kpt_shape: [2, 3]\nflip_idx: [0, 1]\n"), std::string::npos) << yaml;
}

TEST(Lens, DistortionIsOpenCvsModelAndTheWarpItsInverse) {
  const LensDistortion lens{-0.21, 0.06, 0.0012, -0.0007, 0.01};
  // Known points, the model written out here again (cv::projectPoints' order).
  for (const glm::dvec2 p : {glm::dvec2(0.3, -0.2), glm::dvec2(-0.5, 0.25), glm::dvec2(0.0, 0.0)}) {
    const double r2 = p.x * p.x + p.y * p.y;
    const double radial = 1 + lens.k1 * r2 + lens.k2 * r2 * r2 + lens.k3 * r2 * r2 * r2;
    const glm::dvec2 want{p.x * radial + 2 * lens.p1 * p.x * p.y + lens.p2 * (r2 + 2 * p.x * p.x),
                          p.y * radial + lens.p1 * (r2 + 2 * p.y * p.y) + 2 * lens.p2 * p.x * p.y};
    EXPECT_NEAR(glm::length(lens.distort(p) - want), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(lens.undistort(lens.distort(p)) - p), 0.0, 1e-11);
  }
  // The warp: ids that number the ideal image's columns come out where each distorted
  // pixel's source column is.
  const render::PinholeIntrinsics k{100.0, 100.0, 40.0, 30.0};
  const LensWarp warp(lens, k, 80, 60, "--distortion");
  render::IdImage ids;
  ids.width = 80;
  ids.height = 60;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 80; ++x) ids.ids.push_back(std::uint32_t(x + 1));
  ids.depth.assign(ids.ids.size(), 2.0f);
  render::IdImage warped;
  warp.apply(ids, warped);
  for (const glm::ivec2 at : {glm::ivec2(3, 4), glm::ivec2(40, 30), glm::ivec2(70, 50)}) {
    const glm::dvec2 source =
        lens.undistort({(at.x + 0.5 - k.cx) / k.fx, (at.y + 0.5 - k.cy) / k.fy});
    const int column = int(std::floor(k.fx * source.x + k.cx));
    EXPECT_EQ(warped.ids[warped.index(at.x, at.y)], std::uint32_t(column + 1))
        << at.x << "," << at.y;
    EXPECT_FLOAT_EQ(warped.depth[warped.index(at.x, at.y)], 2.0f);  // one surface: its depth
    // A point's pixel through the lens: the forward model on its ideal pixel.
    const glm::dvec2 back = warp.distort_pixel({k.fx * source.x + k.cx, k.fy * source.y + k.cy});
    EXPECT_NEAR(glm::length(back - glm::dvec2(at.x + 0.5, at.y + 0.5)), 0.0, 1e-7);
  }
  EXPECT_TRUE(test::ThrowsError(
      [&] {
        LensWarp({-5.0, 0, 0, 0, 0}, k, 80, 60, "--distortion");
      },
      ErrorCode::kInvalidArgument, "--distortion"));
}

TEST(Lens, NoiseHasItsSigmaAndItsSeed) {
  render::Image grey;
  grey.width = 200;
  grey.height = 100;
  grey.rgb.assign(200 * 100 * 3, 128);
  const SensorNoise noise{2.0, 4.0};
  render::Image a = grey, b = grey, c = grey;
  noise.apply(a, 7);
  noise.apply(b, 7);
  noise.apply(c, 8);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_NE(a.rgb, c.rgb);
  double sum = 0.0, squares = 0.0;
  for (std::uint8_t v : a.rgb) {
    sum += v - 128.0;
    squares += (v - 128.0) * (v - 128.0);
  }
  const double n = double(a.rgb.size());
  const double sigma = std::sqrt(squares / n - (sum / n) * (sum / n));
  const double want = std::sqrt(2.0 * 2.0 + 4.0 * 4.0 * 128.0 / 255.0);  // 3.46
  EXPECT_NEAR(sigma, std::sqrt(want * want + 1.0 / 12.0), 0.05 * want);  // with rounding's
  EXPECT_NEAR(sum / n, 0.0, 0.05);
}

TEST(Masks, ARunAcrossColumnsBoxesTheColumnsItSpans) {
  // Pixels (0, 2) and (1, 0) follow each other in column-major order: one run.
  render::IdImage image = small_ids();
  image.ids = {0, 3, 0, 0, 0, 0, 0, 0, 3, 0, 0, 0};
  const std::vector<InstanceMask> masks = instance_masks(image);
  ASSERT_EQ(masks.size(), 1u);
  EXPECT_EQ(masks[0].counts, (std::vector<std::uint32_t>{2, 2, 8}));
  EXPECT_EQ(std::vector<int>({masks[0].x_min, masks[0].y_min, masks[0].x_max, masks[0].y_max}),
            std::vector<int>({0, 0, 1, 2}));
}

TEST(Landmarks, SnoutTipAndTailForkOfTheBundledFish) {
  for (const char* name : {"blub/fish_low_resolution.obj", "barramundi/BarramundiFish.gltf"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = load_mesh(test::data_path(name));
    const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
    const FishLandmarks marks = find_landmarks(model);
    const BodyFrame& frame = model.rig().components.front().frame;
    const auto x_of = [&](std::size_t v) {
      return glm::dot(glm::dvec3(mesh.positions[v]) - frame.origin, frame.axis_x) / frame.length;
    };
    double x_min = 1e9, x_max = -1e9;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      x_min = std::min(x_min, x_of(v));
      x_max = std::max(x_max, x_of(v));
    }
    EXPECT_EQ(x_of(marks.snout), x_max);
    // The fork is at the back: within the rearmost 15 % of the body.
    EXPECT_LT(x_of(marks.tail_fork) - x_min, 0.15);
    EXPECT_NEAR(marks.fork_fraction, x_max - x_of(marks.tail_fork), 1e-12);
    EXPECT_GT(marks.fork_fraction, 0.85);
    EXPECT_LE(marks.fork_fraction, 1.0 + 1e-12);
  }
}

TEST(Landmarks, TheBodyPatternRunsFromSnoutToTailAndBellyToBack) {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  const std::vector<glm::vec2> pattern = body_pattern(model);
  const std::vector<glm::dvec3> local = rest_in_body_frame(model);
  ASSERT_EQ(pattern.size(), mesh.vertex_count());
  EXPECT_FLOAT_EQ(pattern[find_landmarks(model).snout].x, 0.0f);
  std::size_t top = 0, bottom = 0;
  for (std::size_t v = 0; v < pattern.size(); ++v) {
    EXPECT_GE(pattern[v].x, 0.0f);
    EXPECT_LE(pattern[v].x, 1.0f);
    EXPECT_GE(pattern[v].y, -1.0f - 1e-6f);
    EXPECT_LE(pattern[v].y, 1.0f + 1e-6f);
    if (local[v].y > local[top].y) top = v;
    if (local[v].y < local[bottom].y) bottom = v;
  }
  EXPECT_FLOAT_EQ(pattern[top].y, 1.0f);  // the highest vertex tops its station
  EXPECT_FLOAT_EQ(pattern[bottom].y, -1.0f);
}

TEST(TankView, EveryViewFramesTheWholeTank) {
  const tank::TankSettings settings;
  const float radius = float(0.5 * settings.diameter);
  const float rim = float(1.1 * settings.depth);
  for (const auto& [width, height] : {std::pair{640, 360}, std::pair{360, 640}}) {
    for (CameraView view : {CameraView::kAbove, CameraView::kOblique, CameraView::kSide}) {
      SCOPED_TRACE(std::string(to_string(view)) + " " + std::to_string(width));
      const render::Camera camera = tank_camera(settings, view, width, height);
      camera.validate();
      glm::vec2 low(1e9f), high(-1e9f);
      for (int k = 0; k < 72; ++k) {
        const float angle = 6.2831853f * float(k) / 72.0f;
        for (float y : {0.0f, rim}) {
          const glm::vec3 p{radius * std::cos(angle), y, radius * std::sin(angle)};
          // The side view looks through the near wall: its far half must fit.
          if (view == CameraView::kSide && p.z > 0.0f) continue;
          const glm::vec3 pixel = render::project_to_pixel(camera, width, height, p);
          ASSERT_GT(pixel.z, 0.0f);
          low = glm::min(low, glm::vec2(pixel));
          high = glm::max(high, glm::vec2(pixel));
        }
      }
      EXPECT_GE(low.x, 0.0f);
      EXPECT_GE(low.y, 0.0f);
      EXPECT_LE(high.x, float(width));
      EXPECT_LE(high.y, float(height));
      // Tight: the tank spans most of the frame one way or the other (the side view
      // stands back far enough that the near wall's rim clears the frame's top).
      EXPECT_GT(std::max((high.x - low.x) / float(width), (high.y - low.y) / float(height)),
                view == CameraView::kSide ? 0.7f : 0.8f);
    }
  }
  EXPECT_EQ(parse_camera_view("side", "--camera"), CameraView::kSide);
  EXPECT_THROW(parse_camera_view("top", "--camera"), Error);
}

// A small tank of low-resolution Blubs seen from above, a few frames in.
constexpr int kFrames = 3;
const PictureSettings kAbove = [] {
  PictureSettings settings;
  settings.width = 200;
  settings.height = 150;
  settings.view = CameraView::kAbove;
  return settings;
}();

// `fish` low-resolution Blubs in `hall` (one default tank unless given).
tank::SwimScene small_scene(Context& context, const tank::OutputsFactory& outputs = {},
                            const std::optional<tank::SceneLevels>& levels = std::nullopt,
                            const tank::HallSettings& hall = tank::TankSettings{},
                            std::size_t fish = 8) {
  return tank::SwimScene(context,
                         {{test::data_path("blub/fish_low_resolution.obj"),
                           test::data_path("rigs/blub_low_resolution_swim.rig.json")}},
                         fish, hall, 3, NormalMode::kJacobian, NormalFormat::kFloat32, {}, outputs,
                         levels);
}

// Three levels of half the triangles, a budget of `pixels`.
tank::SceneLevels three_levels(double pixels) {
  tank::SceneLevels levels;
  levels.levels.levels = 3;
  levels.levels.triangle_ratio = 0.5;
  levels.choice.pixel_budget = pixels;
  return levels;
}

// As `finflex swim` draws it: the renderer first, an OpenCL context sharing its GL
// context where the platform can (on PoCL it cannot), the hand-off's path (`wanted`,
// or the first that runs: external memory where Vulkan and GL can import, as Mesa's
// lavapipe and llvmpipe can beside PoCL), and the species' deformations writing the
// renderer's buffers.
// (Or `fish` fish in `hall`, seen as `view` says.)
struct SmallTank {
  render::Renderer renderer;
  GlSharingContext opencl;
  HandOff hand_off;
  tank::SwimScene scene;
  TankPictures pictures;
  explicit SmallTank(std::optional<HandOffPath> wanted = std::nullopt,
                     const std::optional<tank::SceneLevels>& levels = std::nullopt,
                     const tank::HallSettings& hall = tank::TankSettings{}, std::size_t fish = 8,
                     const PictureSettings& view = kAbove)
      : renderer(render_settings(view)),
        opencl(make_gl_sharing_context(test::shared_context().description().device_name,
                                       renderer.egl_display(), renderer.egl_context())),
        hand_off(choose_hand_off(renderer, *opencl.context, opencl.why_not, wanted)),
        scene(small_scene(*opencl.context, gl_outputs(renderer, hand_off), levels, hall, fish)),
        pictures(renderer, scene, view) {
    for (int frame = 0; frame < kFrames; ++frame) scene.enqueue_frame(1.0 / 30.0);
  }
};

render::Image empty_tank(TankPictures& pictures) {
  pictures.renderer().render(pictures.look(), pictures.camera(), {});
  return pictures.renderer().read_image();
}

// The GL buffer `buffer` of `renderer`, as floats.
std::vector<float> gl_floats(render::Renderer& renderer, render::BufferId buffer) {
  renderer.make_current();
  std::vector<float> out(renderer.buffer_bytes(buffer) / sizeof(float));
  glBindBuffer(GL_ARRAY_BUFFER, renderer.gl_buffer(buffer));
  glGetBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(out.size() * sizeof(float)),
                     out.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return out;
}

TEST(TankPictures, TheDeformationWritesTheRenderersBuffersOnTheFirstPathThatRuns) {
  SmallTank tank;
  EXPECT_EQ(tank.pictures.hand_off_path(), tank.hand_off.path);
  std::printf("hand-off path: %s (not external: '%s'; not shared: '%s')\n",
              to_string(tank.pictures.hand_off_path()), tank.hand_off.why_not_external.c_str(),
              tank.hand_off.why_not_shared.c_str());
  // Each path before the chosen one says why it could not run.
  if (tank.hand_off.path != HandOffPath::kExternal) {
    EXPECT_FALSE(tank.hand_off.why_not_external.empty());
  }
  if (tank.hand_off.path == HandOffPath::kCopy) {
    EXPECT_FALSE(tank.hand_off.why_not_shared.empty());
  }
  // External memory ordered on the GPU alternates two sets of buffers (a frame's
  // kernels never wait for the last frame's draw); otherwise one set, or none.
  const auto* outputs = dynamic_cast<GlSpeciesOutputs*>(tank.scene.species()[0].outputs.get());
  ASSERT_NE(outputs, nullptr);
  const std::size_t sets = tank.hand_off.path != HandOffPath::kExternal ? 0
                           : tank.pictures.device_ordered()             ? 2
                                                                        : 1;
  EXPECT_EQ(outputs->buffer_sets(), sets);
  // A scene whose outputs are the engine's own device buffers cannot be drawn.
  tank::SwimScene plain = small_scene(test::shared_context());
  try {
    TankPictures refused(tank.renderer, plain, kAbove);
    ADD_FAILURE() << "a scene without GL outputs was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "scene");
  }
}

TEST(TankPictures, TheHandOffDrawsWhatTheEngineComputed) {
  SmallTank tank;
  tank.pictures.draw();
  const render::Image handed = tank.pictures.read_image();
  // The oracle: the same tank, the same frames, deformed into the engine's own device
  // buffers (no GL anywhere) and read back to the host (ClDeformer::read: mesh order).
  tank::SwimScene plain = small_scene(test::shared_context());
  for (int frame = 0; frame < kFrames; ++frame) plain.enqueue_frame(1.0 / 30.0);
  tank::Species& species = plain.species()[0];
  const DeformedBatch<float> host = species.deformer->read(species.batch());
  const std::size_t instances = host.shape.instance_count;
  const std::size_t vertices = host.shape.vertex_count;

  // The GL buffers the picture was drawn from hold exactly the engine's vertices, in
  // FinFlex's planes over the deformer's slots.
  auto* outputs = dynamic_cast<GlSpeciesOutputs*>(tank.scene.species()[0].outputs.get());
  ASSERT_NE(outputs, nullptr);
  const std::size_t plane = outputs->layout().positions.plane_stride;
  const std::vector<std::uint32_t>& slot_of = tank.scene.species()[0].deformer->slot_of_vertex();
  const std::vector<float> gl_positions = gl_floats(tank.renderer, outputs->positions());
  const std::vector<float> gl_normals = gl_floats(tank.renderer, outputs->normals());
  ASSERT_GE(gl_positions.size(), instances * 3 * plane);
  ASSERT_GE(gl_normals.size(), instances * 3 * plane);
  for (std::size_t i = 0; i < instances; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      for (int c = 0; c < 3; ++c) {
        const std::size_t at = (3 * i + std::size_t(c)) * plane + slot_of[v];
        ASSERT_EQ(gl_positions[at], host.position(i, v)[c]) << "instance " << i << " vertex " << v;
        ASSERT_EQ(gl_normals[at], host.normal(i, v)[c]) << "instance " << i << " vertex " << v;
      }
    }
  }

  // And the picture is the engine's vertices drawn from the host with the mesh's own
  // triangles, pixel for pixel.
  std::vector<float> positions(instances * 3 * vertices);
  std::vector<float> normals(positions.size());
  for (std::size_t i = 0; i < instances; ++i) {
    for (std::size_t v = 0; v < vertices; ++v) {
      for (int c = 0; c < 3; ++c) {
        positions[(i * vertices + v) * 3 + std::size_t(c)] = host.position(i, v)[c];
        normals[(i * vertices + v) * 3 + std::size_t(c)] = host.normal(i, v)[c];
      }
    }
  }
  render::Renderer& renderer = tank.pictures.renderer();
  const Mesh& rest = species.swim.model().mesh();
  render::FishDraw draw;
  draw.mesh =
      renderer.add_mesh(rest.indices, rest.vertex_count(), body_pattern(species.swim.model()));
  draw.albedo = species_albedo(species.name, 0);
  draw.instance_count = instances;
  std::vector<std::uint32_t> ids(instances);  // 1 + the fish's index: one species
  for (std::size_t i = 0; i < instances; ++i) ids[i] = std::uint32_t(i + 1);
  draw.ids = ids.data();
  const auto layout = render::StreamLayout::interleaved(vertices);
  draw.positions = render::VertexStream::from_host(positions.data(), positions.size() * 4, layout);
  draw.normals = render::VertexStream::from_host(normals.data(), normals.size() * 4, layout);
  renderer.render(tank.pictures.look(), tank.pictures.camera(), {draw});
  const render::Image read = renderer.read_image();
  EXPECT_EQ(handed.rgb, read.rgb);
  EXPECT_NE(handed.rgb, empty_tank(tank.pictures).rgb);  // the fish are in the picture
}

// A kernel that keeps the OpenCL queue busy for some tens of milliseconds (one
// work-item's chain of dependent multiply-adds), enqueued before a frame's kernels: a
// consumer that does not wait for the frame draws the one before it.
void keep_the_queue_busy(Context& context) {
  static const char* source = R"(
    __kernel void busy(__global float* out, int iterations) {
      float x = 1.0f;
      for (int k = 0; k < iterations; ++k) x = x * 0.99999f + 0.5f;
      out[0] = x;
    })";
  cl::Program program(context.context(), source, true);
  cl::Kernel kernel(program, "busy");
  cl::Buffer out(context.context(), CL_MEM_READ_WRITE, sizeof(float));
  kernel.setArg(0, out);
  kernel.setArg(1, 20000000);
  check_cl(
      context.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(1), cl::NDRange(1)),
      "clEnqueueNDRangeKernel (busy)");
}

// Frames 3..5 of the small tank on `path`, colour and ids; empty when the path cannot
// run here (its reason printed). `busy`: each frame's kernels wait behind
// keep_the_queue_busy.
std::vector<std::vector<std::uint8_t>> frames_on(HandOffPath path, bool busy = false) {
  std::vector<std::vector<std::uint8_t>> out;
  std::unique_ptr<SmallTank> tank;
  try {
    tank = std::make_unique<SmallTank>(path);
  } catch (const Error& e) {
    std::printf("%s: %s\n", to_string(path), e.what());
    EXPECT_EQ(e.field(), "--hand-off");
    return out;
  }
  for (int frame = 0; frame < 3; ++frame) {
    if (busy) keep_the_queue_busy(*tank->opencl.context);
    tank->scene.enqueue_frame(1.0 / 30.0);
    tank->pictures.draw();
    out.push_back(tank->pictures.read_image().rgb);
    const render::IdImage& ids = tank->pictures.draw_ids();
    out.emplace_back(reinterpret_cast<const std::uint8_t*>(ids.ids.data()),
                     reinterpret_cast<const std::uint8_t*>(ids.ids.data() + ids.ids.size()));
  }
  return out;
}

TEST(TankPictures, EveryHandOffPathDrawsTheSameFramesByteForByte) {
  const std::vector<std::vector<std::uint8_t>> copy = frames_on(HandOffPath::kCopy);
  ASSERT_EQ(copy.size(), 6u);
  int compared = 0;
  for (HandOffPath path : {HandOffPath::kExternal, HandOffPath::kShared}) {
    const std::vector<std::vector<std::uint8_t>> frames = frames_on(path);
    if (frames.empty()) continue;
    ASSERT_EQ(frames.size(), copy.size());
    for (std::size_t k = 0; k < frames.size(); ++k) {
      EXPECT_TRUE(frames[k] == copy[k]) << to_string(path) << ": picture " << k;
    }
    ++compared;
  }
  std::printf("paths compared with the copy: %d\n", compared);
  // Mesa's lavapipe and llvmpipe import each other's memory: on a CPU machine with
  // them (CI) the external path runs.
  if (std::getenv("FINFLEX_EXPECT_EXTERNAL_MEMORY") != nullptr) {
    EXPECT_GE(compared, 1);
  }
}

// The frame orders itself (semaphores on the GPU, else waits on the host): a frame
// whose kernels are held back behind a long one is still drawn from its own vertices.
TEST(TankPictures, AFrameIsNeverDrawnBeforeItsKernelsFinish) {
  const std::vector<std::vector<std::uint8_t>> copy = frames_on(HandOffPath::kCopy);
  const std::vector<std::vector<std::uint8_t>> external = frames_on(HandOffPath::kExternal, true);
  if (external.empty()) GTEST_SKIP() << "no external memory here";
  ASSERT_EQ(external.size(), copy.size());
  for (std::size_t k = 0; k < copy.size(); ++k) {
    EXPECT_TRUE(external[k] == copy[k]) << "picture " << k;
  }
}

// The reference draw: the same triangles the cheapest way, timed on the GPU; the
// frame's image stays the colour pass's. A stream it cannot read as vertex attributes
// (host memory) is named.
TEST(TankPictures, TheReferenceDrawIsTimedAndLeavesTheImage) {
  SmallTank tank;
  tank.pictures.draw();
  const render::Image before = tank.pictures.read_image();
  tank.pictures.draw_reference();
  tank.renderer.finish();
  EXPECT_TRUE(tank.pictures.read_image().rgb == before.rgb);
  tank.pictures.draw_reference();  // a second frame, so the first timed one has a result
  tank.renderer.finish();
  const double seconds = tank.renderer.gpu_reference_seconds();
  EXPECT_GT(seconds, 0.0);
  EXPECT_LT(seconds, 10.0);
  const std::vector<float> host(3 * 64, 0.0f);
  render::FishDraw draw;
  draw.mesh = tank.renderer.add_mesh({0, 1, 2}, 64);
  draw.instance_count = 1;
  draw.positions = render::VertexStream::from_host(host.data(), host.size() * 4,
                                                   render::StreamLayout::interleaved(64));
  draw.normals = draw.positions;
  try {
    tank.renderer.render_reference(tank.pictures.look(), tank.pictures.camera(), {draw});
    ADD_FAILURE() << "a host stream was drawn by the reference draw";
  } catch (const render::RenderError& e) {
    EXPECT_EQ(e.field(), "fish[0].positions");
  }
}

TEST(TankPictures, TheIdPassCoversTheFishWithTheirTankIds) {
  SmallTank tank;
  tank.pictures.draw();
  const render::Image colour = tank.pictures.read_image();
  const render::IdImage ids = tank.pictures.draw_ids();
  const render::Image empty = empty_tank(tank.pictures);
  ASSERT_EQ(ids.ids.size(), std::size_t(200 * 150));
  std::set<std::uint32_t> seen;
  std::vector<bool> fish_in_colour(ids.ids.size()), fish_in_ids(ids.ids.size());
  for (int y = 0; y < ids.height; ++y) {
    for (int x = 0; x < ids.width; ++x) {
      const std::size_t k = ids.index(x, y);
      int difference = 0;
      for (int c = 0; c < 3; ++c) {
        difference += std::abs(int(colour.pixel(x, y)[c]) - int(empty.pixel(x, y)[c]));
      }
      fish_in_colour[k] = difference > 12;
      fish_in_ids[k] = ids.ids[k] != 0;
      EXPECT_GT(ids.depth[k], 0.0f);
      if (ids.ids[k] == 0) continue;
      seen.insert(ids.ids[k]);
      // A fish is between the camera and the floor.
      EXPECT_GT(ids.depth[k], 0.5f);
      EXPECT_LT(ids.depth[k], tank.pictures.camera().position.y);
    }
  }
  // Where a fish covers the pixel's centre, its colour shows; where the antialiased
  // colour shows a fish, a fish covers that pixel's centre or a neighbour's (edges).
  const auto near_a = [&](const std::vector<bool>& mask, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int u = x + dx, v = y + dy;
        if (u >= 0 && v >= 0 && u < ids.width && v < ids.height && mask[ids.index(u, v)])
          return true;
      }
    }
    return false;
  };
  std::size_t in_ids = 0, id_shown = 0, in_colour = 0, colour_covered = 0;
  for (int y = 0; y < ids.height; ++y) {
    for (int x = 0; x < ids.width; ++x) {
      const std::size_t k = ids.index(x, y);
      in_ids += fish_in_ids[k];
      id_shown += fish_in_ids[k] && fish_in_colour[k];
      in_colour += fish_in_colour[k];
      colour_covered += fish_in_colour[k] && near_a(fish_in_ids, x, y);
    }
  }
  ASSERT_GT(in_ids, 100u);
  EXPECT_GT(double(id_shown) / double(in_ids), 0.97);
  EXPECT_GT(double(colour_covered) / double(in_colour), 0.97);
  // Ids are 1 + the tank's fish indices, and every fish is seen from above.
  EXPECT_EQ(seen.size(), 8u);
  EXPECT_EQ(*seen.begin(), 1u);
  EXPECT_EQ(*seen.rbegin(), 8u);
}

// The same frame at its levels and at full detail: every fish still drawn; with a
// budget no coarse level meets, at level 0 the very same pixels; at a pixel, coarser
// levels and the same fish where the same pixels are but along the fish's edges.
// Drawn from the GPU's lists (external memory), the same as from the host's.
TEST(TankPictures, FishAtTheirLevelsCoverWhatTheFullMeshCovers) {
  SmallTank full;
  full.pictures.draw();
  const render::IdImage want = full.pictures.draw_ids();
  for (double pixels : {0.01, 1.0}) {
    SmallTank leveled(std::nullopt, three_levels(pixels));
    leveled.pictures.draw();
    const render::IdImage got = leveled.pictures.draw_ids();
    const tank::SwimScene::LevelCounts counts = leveled.scene.level_counts(0);
    std::size_t drawn = 0;
    for (std::size_t n : counts.per_level) drawn += n;
    EXPECT_EQ(drawn, 8u) << pixels << " pixels";
    ASSERT_EQ(got.ids.size(), want.ids.size());
    std::size_t covered = 0, agree = 0;
    std::set<std::uint32_t> seen;
    for (std::size_t k = 0; k < want.ids.size(); ++k) {
      if (got.ids[k] != 0) seen.insert(got.ids[k]);
      if (want.ids[k] == 0 && got.ids[k] == 0) continue;
      ++covered;
      agree += want.ids[k] == got.ids[k];
    }
    ASSERT_GT(covered, 100u);
    std::printf("%g pixels: fish per level %zu/%zu/%zu, %.4f of the fish pixels agree\n", pixels,
                counts.per_level[0], counts.per_level[1], counts.per_level[2],
                double(agree) / double(covered));
    EXPECT_EQ(seen.size(), 8u) << pixels << " pixels";
    if (pixels < 1.0) {
      EXPECT_EQ(counts.per_level[0], 8u);
      EXPECT_EQ(agree, covered);
    } else {
      EXPECT_GT(counts.per_level.back(), 0u);
      EXPECT_GT(double(agree) / double(covered), 0.9);
      // The GPU's lists (external memory: the command and entries copied beside each
      // level's outputs, one indirect draw per level) draw what the host's draw.
      if (leveled.hand_off.path == HandOffPath::kExternal &&
          leveled.renderer.device().device_lists) {
        SmallTank host(HandOffPath::kCopy, three_levels(pixels));
        host.pictures.draw();
        EXPECT_EQ(host.pictures.draw_ids().ids, got.ids);
        EXPECT_EQ(host.pictures.read_image().rgb, leveled.pictures.read_image().rgb);
      }
    }
  }
}

TEST(TankPictures, FishBehindOtherTanksWallsAreCulledAndNothingSeenChanges) {
  // A hall of 3 x 3 tanks from its gangway: the second row's fish behind the first
  // row's walls are neither deformed nor drawn, and the picture and the ids are the
  // full-detail frame's, pixel for pixel (at a budget no coarse level meets).
  tank::HallSettings hall;
  hall.tanks = 9;
  hall.columns = 3;
  hall.tank.diameter = 6.0;  // tanks as deep as a farm's of 6,000 fish (the gangway's
  hall.tank.depth = 2.0;     // camera 4 m up sees less of the far rows over them)
  PictureSettings view;
  view.width = 320;
  view.height = 180;
  const std::size_t fish = 270;
  SmallTank full(std::nullopt, std::nullopt, hall, fish, view);
  full.pictures.draw();
  const render::IdImage want = full.pictures.draw_ids();
  const auto drawn = [](const tank::SwimScene& scene) {
    std::size_t n = 0;
    for (std::size_t count : scene.level_counts(0).per_level) n += count;
    return n;
  };
  tank::SceneLevels open = three_levels(0.01);
  open.wall_occlusion = false;
  SmallTank without(std::nullopt, open, hall, fish, view);
  SmallTank with(std::nullopt, three_levels(0.01), hall, fish, view);
  with.pictures.draw();
  const render::IdImage got = with.pictures.draw_ids();
  const std::size_t in_view = drawn(without.scene), hidden = in_view - drawn(with.scene);
  std::printf("of %zu fish %zu in view, %zu of them hidden by walls\n", fish, in_view, hidden);
  EXPECT_GT(hidden, in_view / 10);
  EXPECT_EQ(with.scene.level_counts(0).per_level[0], drawn(with.scene));
  EXPECT_EQ(got.ids, want.ids);
  EXPECT_EQ(with.pictures.read_image().rgb, full.pictures.read_image().rgb);
  std::set<std::uint32_t> seen(want.ids.begin(), want.ids.end());
  seen.erase(0);
  EXPECT_GT(seen.size(), fish / 4);
}

TEST(TankPictures, IdPassesInFlightComeBackInTheirOrderAsDrawn) {
  SmallTank tank;
  render::Renderer& renderer = tank.pictures.renderer();
  const std::size_t in_flight = renderer.settings().frames_in_flight;
  std::vector<render::IdImage> now;  // each frame's id pass, read at once
  for (std::size_t k = 0; k < in_flight; ++k) {
    tank.scene.enqueue_frame(1.0 / 30.0);
    tank.pictures.draw();
    now.push_back(tank.pictures.draw_ids());
    tank.pictures.request_ids();
  }
  EXPECT_EQ(renderer.ids_pending(), in_flight);
  const auto field_of = [](const std::function<void()>& step) {
    try {
      step();
    } catch (const render::RenderError& error) {
      return error.field();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(field_of([&] { renderer.request_ids(); }), "request_ids");
  render::IdImage ids;
  for (std::size_t k = 0; k < in_flight; ++k) {
    renderer.take_ids(ids);
    EXPECT_EQ(ids.ids, now[k].ids) << "frame " << k;
    EXPECT_EQ(ids.depth, now[k].depth) << "frame " << k;
  }
  EXPECT_NE(now.front().ids, now.back().ids);  // the fish swam
  EXPECT_EQ(field_of([&] { renderer.take_ids(ids); }), "take_ids");
  renderer.finish();
  const double seconds = renderer.gpu_id_seconds();
  EXPECT_GT(seconds, 0.0);
  EXPECT_LT(seconds, 10.0);
}

TEST(TankPictures, AnnotationsNeedTheFramesIdPassAndWriteNothingWithout) {
  SmallTank tank;
  const std::string folder = test::temp_path("annotate_without_ids");
  std::filesystem::remove_all(folder);
  CocoDataset dataset(folder, tank.scene, {tank.pictures.camera()}, kAbove.width, kAbove.height,
                      nlohmann::ordered_json::object());
  CocoDataset::FrameTruth truth = dataset.capture(0, 0.0, "frames/frame_000000.png");
  try {
    (void)dataset.annotate(truth);
    ADD_FAILURE() << "a frame without its id pass was annotated";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "ids");
  }
  EXPECT_TRUE(std::filesystem::is_empty(std::filesystem::path(folder) / "masks"));
  truth.ids = tank.pictures.draw_ids();
  EXPECT_NO_THROW((void)dataset.annotate(truth));
  EXPECT_FALSE(std::filesystem::is_empty(std::filesystem::path(folder) / "masks"));
  std::filesystem::remove_all(folder);
}

TEST(TankPictures, TheIdPassNeedsAnIdPerInstance) {
  SmallTank tank;
  render::Renderer& renderer = tank.pictures.renderer();
  const Mesh& rest = tank.scene.species()[0].swim.model().mesh();
  const std::vector<float> one(rest.vertex_count() * 3, 0.5f);
  render::FishDraw draw;
  draw.mesh = renderer.add_mesh(rest.indices, rest.vertex_count());
  draw.instance_count = 2;
  // Both instances read one set of vertices: a zero instance stride.
  render::StreamLayout shared = render::StreamLayout::interleaved(rest.vertex_count());
  shared.instance_stride = 0;
  draw.positions = render::VertexStream::from_host(one.data(), one.size() * 4, shared);
  draw.normals = draw.positions;
  const auto field_of = [&](const render::FishDraw& d) {
    try {
      renderer.render_ids(tank.pictures.look(), tank.pictures.camera(), {d});
    } catch (const render::RenderError& error) {
      return error.field();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(field_of(draw), "fish[0].ids");
  const std::uint32_t with_zero[] = {4, 0};
  draw.ids = with_zero;
  EXPECT_EQ(field_of(draw), "fish[0].ids[1]");
  const std::uint32_t good[] = {4, 5};
  draw.ids = good;
  EXPECT_EQ(field_of(draw), "accepted");
}

}  // namespace
}  // namespace finflex::pictures
