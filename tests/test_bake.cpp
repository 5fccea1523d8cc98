// Bakes of one swim cycle (apps/bake) for engines without OpenCL: the cycle's time step
// makes the wave's phase wrap exactly; the glTF morph animation loads back with
// tinygltf with a target per frame and one-hot weights, and base + target k is the
// engine's frame k and agrees with the CPU reference driven independently; the vertex
// animation textures decode to within their quantisation; the frame meshes hold the
// frames.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include "finflex/finflex.hpp"
#include "frame_meshes.hpp"
#include "morph_animation.hpp"
#include "support/test_support.hpp"
#include "swim_cycle.hpp"
#include "vertex_animation_texture.hpp"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace finflex::bake {
namespace {

namespace fs = std::filesystem;

const SwimModel& swim_model() {
  static const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  static const SwimModel swim(RiggedMesh(
      mesh,
      resolve_rig(load_rig_file(test::data_path("rigs/blub_low_resolution_swim.rig.json")), mesh)));
  return swim;
}

CycleSettings settings(std::size_t frames) {
  CycleSettings s;
  s.frames = frames;
  s.length_m = 0.35;
  s.speed = 1.2;
  return s;
}

double largest_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    largest = std::max(largest, double(std::fabs(a[i] - b[i])));
  return largest;
}

std::vector<float> row(const RigParameters& p, std::size_t instance) {
  const std::size_t n = p.values_per_instance();
  return {p.values().begin() + std::ptrdiff_t(instance * n),
          p.values().begin() + std::ptrdiff_t((instance + 1) * n)};
}

TEST(SwimCycle, TheTimeStepWrapsThePhaseExactly) {
  const std::size_t n = 12;
  const SwimCycle cycle = plan_cycle(swim_model(), settings(n));
  EXPECT_NEAR(cycle.frequency_hz * cycle.dt_s * double(n), 1.0, 1e-12);
  EXPECT_NEAR(cycle.period_s, 1.0 / cycle.frequency_hz, 1e-12);
  // The driver stepped on by the same dt repeats itself every N steps: steps N and 2N
  // give the same parameters (frame 0), as do steps 1 and N + 1 (frame 1).
  SwimReference fish(swim_model(), {0.35f});
  SwimInput input;
  input.yaw = -1.5707963f;
  input.speed = float(1.2 * double(0.35f));
  std::vector<std::vector<float>> steps;
  for (std::size_t k = 1; k <= 2 * n + 1; ++k) {
    fish.step({input}, cycle.dt_s);
    steps.push_back(row(fish.parameters(), 0));
  }
  EXPECT_LT(largest_difference(steps[n - 1], steps[2 * n - 1]), 1e-5);
  EXPECT_LT(largest_difference(steps[0], steps[n]), 1e-5);
  EXPECT_LT(largest_difference(steps[n - 1], row(cycle.parameters, 0)), 1e-5);
  EXPECT_LT(largest_difference(steps[0], row(cycle.parameters, 1)), 1e-5);
  // The rest pose is all zeros; every frame's placement is the same.
  for (float v : row(cycle.parameters, n)) EXPECT_EQ(v, 0.0f);
  ASSERT_EQ(cycle.placements.size(), n + 1);
  EXPECT_EQ(cycle.placements[0].position, glm::vec3(0.0f));
  EXPECT_FLOAT_EQ(cycle.placements[0].length, 0.35f);
  // Bad settings are named.
  for (const auto& [bad, field] : {std::pair{[] {
                                               auto s = settings(1);
                                               return s;
                                             }(),
                                             "frames"},
                                   std::pair{[] {
                                               auto s = settings(8);
                                               s.length_m = 0.0;
                                               return s;
                                             }(),
                                             "length"},
                                   std::pair{[] {
                                               auto s = settings(8);
                                               s.speed = -1.0;
                                               return s;
                                             }(),
                                             "speed"}}) {
    try {
      bad.validate();
      ADD_FAILURE() << field;
    } catch (const Error& e) {
      EXPECT_EQ(e.field(), field);
    }
  }
}

// Positions (or normals) of the glTF's base plus target k (-1: the base alone).
std::vector<glm::vec3> gltf_attribute(const tinygltf::Model& model, const std::string& name,
                                      int target) {
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  const auto read = [&](int accessor_index) {
    const tinygltf::Accessor& accessor = model.accessors[std::size_t(accessor_index)];
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(accessor.bufferView)];
    const auto* data =
        reinterpret_cast<const float*>(model.buffers[std::size_t(view.buffer)].data.data() +
                                       view.byteOffset + accessor.byteOffset);
    std::vector<glm::vec3> out(accessor.count);
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = {data[3 * i], data[3 * i + 1], data[3 * i + 2]};
    return out;
  };
  std::vector<glm::vec3> values = read(primitive.attributes.at(name));
  if (target >= 0) {
    const std::vector<glm::vec3> delta = read(primitive.targets[std::size_t(target)].at(name));
    for (std::size_t i = 0; i < values.size(); ++i) values[i] += delta[i];
  }
  return values;
}

std::vector<float> scalars(const tinygltf::Model& model, int accessor_index) {
  const tinygltf::Accessor& accessor = model.accessors[std::size_t(accessor_index)];
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(accessor.bufferView)];
  const auto* data = reinterpret_cast<const float*>(
      model.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + accessor.byteOffset);
  return {data, data + accessor.count};
}

TEST(Bake, TheGltfAnimationLoadsBackAndIsTheEnginesCycle) {
  const std::size_t n = 10;
  const BakedCycle baked = bake_cycle(test::shared_context(), swim_model(), settings(n));
  const std::string path = test::temp_path("blub_swim.glb");
  const Mesh& mesh = swim_model().model().mesh();
  write_morph_animation(path, "blub", mesh, baked);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path)) << error;
  ASSERT_EQ(model.meshes.size(), 1u);
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  ASSERT_EQ(primitive.targets.size(), n);
  EXPECT_EQ(model.meshes[0].weights.size(), n);
  EXPECT_EQ(model.accessors[std::size_t(primitive.indices)].count, mesh.indices.size());
  // The animation: N + 1 keys k T / N over the mesh's weights, one-hot, the last key
  // the first frame again.
  ASSERT_EQ(model.animations.size(), 1u);
  const tinygltf::Animation& animation = model.animations[0];
  ASSERT_EQ(animation.channels.size(), 1u);
  EXPECT_EQ(animation.channels[0].target_path, "weights");
  EXPECT_EQ(animation.channels[0].target_node, 0);
  const tinygltf::AnimationSampler& sampler = animation.samplers[0];
  EXPECT_EQ(sampler.interpolation, "LINEAR");
  const std::vector<float> times = scalars(model, sampler.input);
  const std::vector<float> weights = scalars(model, sampler.output);
  ASSERT_EQ(times.size(), n + 1);
  ASSERT_EQ(weights.size(), (n + 1) * n);
  EXPECT_NEAR(times.back(), baked.cycle.period_s, 1e-6);
  for (std::size_t k = 0; k <= n; ++k) {
    EXPECT_NEAR(times[k], double(k) * baked.cycle.dt_s, 1e-6);
    for (std::size_t t = 0; t < n; ++t) EXPECT_EQ(weights[k * n + t], t == k % n ? 1.0f : 0.0f);
  }

  // Base + target k is the engine's frame k (float rounding of the difference).
  DeformedBatch<float> loaded;
  BatchShape layout;
  layout.vertex_count = mesh.vertex_count();
  layout.instance_count = n + 1;
  layout.plane_stride = padded_plane_stride(mesh.vertex_count());
  loaded.resize(layout);
  double largest = 0.0;
  for (std::size_t k = 0; k <= n; ++k) {
    const int target = k == n ? -1 : int(k);
    const std::vector<glm::vec3> p = gltf_attribute(model, "POSITION", target);
    const std::vector<glm::vec3> q = gltf_attribute(model, "NORMAL", target);
    for (std::size_t v = 0; v < p.size(); ++v) {
      largest = std::max(largest, double(glm::length(p[v] - baked.batch.position(k, v))));
      loaded.scatter(loaded.positions, k, v, p[v]);
      loaded.scatter(loaded.normals, k, v, q[v]);
    }
  }
  EXPECT_LT(largest, 1e-6);  // metres

  // And the CPU reference agrees, driven here on its own at the bake's time step.
  SwimReference fish(swim_model(), {0.35f});
  SwimInput input;
  input.yaw = -1.5707963f;
  input.speed = float(1.2 * double(0.35f));
  RigParameters values(swim_model().model(), n + 1);
  const std::size_t per = values.values_per_instance();
  for (std::size_t k = 1; k <= n; ++k) {
    fish.step({input}, baked.cycle.period_s / double(n));
    std::copy_n(fish.parameters().values().begin(), per,
                values.values().begin() + std::ptrdiff_t((k % n) * per));
  }
  std::vector<Placement> placements(n + 1, fish.placements()[0]);
  ReferenceJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.placements = placements.data();
  job.normals = NormalMode::kJacobian;
  DeformedBatch<double> exact;
  job.outputs = &exact;
  run_reference(swim_model().model(), job);
  const AccuracyReport report = compare_to_reference(
      swim_model().model(), values.view(), NormalMode::kJacobian, loaded, exact, placements.data());
  EXPECT_TRUE(report.within_tolerance())
      << report.max_position_ratio << " " << report.max_normal_ratio;

  // No jump where it loops: frame N-1 to frame 0 moves as much as one frame to the next.
  double consecutive = 0.0, wrap = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    double step = 0.0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      step = std::max(step, double(glm::length(baked.batch.position((k + 1) % n, v) -
                                               baked.batch.position(k, v))));
    }
    if (k + 1 == n) {
      wrap = step;
    } else {
      consecutive += step / double(n - 1);
    }
  }
  EXPECT_GT(wrap, 0.5 * consecutive);
  EXPECT_LT(wrap, 1.5 * consecutive);
  // Lengths are metres: the straight fish is as long as asked.
  double z_min = 1e9, z_max = -1e9;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    z_min = std::min(z_min, double(baked.batch.position(n, v).z));
    z_max = std::max(z_max, double(baked.batch.position(n, v).z));
  }
  EXPECT_NEAR(z_max - z_min, 0.35, 0.02);
  EXPECT_GT(z_max, 0.0);  // the head towards +z
}

std::vector<std::uint16_t> read_png16(const std::string& path, int& width, int& height) {
  int channels = 0;
  stbi_us* data = stbi_load_16(path.c_str(), &width, &height, &channels, 3);
  EXPECT_NE(data, nullptr) << path;
  if (data == nullptr) return {};
  EXPECT_EQ(channels, 3);
  std::vector<std::uint16_t> out(data, data + std::size_t(width) * std::size_t(height) * 3);
  stbi_image_free(data);
  return out;
}

TEST(Bake, VertexAnimationTexturesDecodeWithinTheirQuantisation) {
  const std::size_t n = 6;
  const BakedCycle baked = bake_cycle(test::shared_context(), swim_model(), settings(n));
  const std::string folder = fs::path(test::temp_path("x")).parent_path().string();
  const Mesh& mesh = swim_model().model().mesh();
  // 945 vertices in rows of at most 400: three rows a frame.
  write_vertex_animation_texture(folder, "blub", mesh, baked, 400);
  nlohmann::json json;
  std::ifstream(folder + "/blub_vat.json") >> json;
  ASSERT_EQ(json["texture_width"], 400);
  ASSERT_EQ(json["rows_per_frame"], 3);
  ASSERT_EQ(json["frames"], n);
  EXPECT_NEAR(json["period_s"].get<double>(), baked.cycle.period_s, 1e-12);
  int width = 0, height = 0;
  const std::vector<std::uint16_t> positions =
      read_png16(folder + "/blub_vat_positions.png", width, height);
  ASSERT_EQ(width, 400);
  ASSERT_EQ(height, int(3 * n));
  const std::vector<std::uint16_t> normals =
      read_png16(folder + "/blub_vat_normals.png", width, height);
  const glm::dvec3 lo(json["bounds_min"][0], json["bounds_min"][1], json["bounds_min"][2]);
  const glm::dvec3 hi(json["bounds_max"][0], json["bounds_max"][1], json["bounds_max"][2]);
  const glm::dvec3 half_step = (hi - lo) / 131070.0;
  double worst_position = 0.0, worst_normal = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      // The JSON's texel formula.
      const std::size_t texel = (k * 3 + v / 400) * 400 + v % 400;
      glm::dvec3 p, q;
      for (int c = 0; c < 3; ++c) {
        p[c] = lo[c] + double(positions[texel * 3 + std::size_t(c)]) / 65535.0 * (hi[c] - lo[c]);
        q[c] = 2.0 * double(normals[texel * 3 + std::size_t(c)]) / 65535.0 - 1.0;
      }
      const glm::dvec3 exact(baked.batch.position(k, v));
      for (int c = 0; c < 3; ++c) {
        worst_position = std::max(worst_position, std::fabs(p[c] - exact[c]) / half_step[c]);
      }
      worst_normal = std::max(
          worst_normal,
          glm::length(glm::normalize(q) - glm::normalize(glm::dvec3(baked.batch.normal(k, v)))));
    }
  }
  EXPECT_LE(worst_position, 1.0 + 1e-3);  // within half a quantisation step
  EXPECT_LT(worst_normal, 3.0 / 65535.0);
  // The shader snippet carries the same numbers; the mesh has the lookup coordinates.
  std::ifstream glsl_file(folder + "/blub_vat.glsl");
  const std::string glsl((std::istreambuf_iterator<char>(glsl_file)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(glsl.find("const int VAT_WIDTH = 400;"), std::string::npos);
  EXPECT_NE(glsl.find("const int VAT_ROWS_PER_FRAME = 3;"), std::string::npos);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, folder + "/blub_vat_mesh.glb"))
      << error;
  const tinygltf::Accessor& lookup =
      model.accessors[std::size_t(model.meshes[0].primitives[0].attributes.at("TEXCOORD_1"))];
  EXPECT_EQ(lookup.count, mesh.vertex_count());
  EXPECT_THROW(vat_layout(baked, 0), Error);
}

TEST(Bake, FrameMeshesHoldEveryFrame) {
  const std::size_t n = 4;
  const BakedCycle baked = bake_cycle(test::shared_context(), swim_model(), settings(n));
  const std::string folder = fs::path(test::temp_path("x")).parent_path().string();
  write_frame_meshes(folder, "blub", "obj", swim_model().model().mesh(), baked);
  for (std::size_t k = 0; k < n; ++k) {
    const Mesh frame = load_mesh(folder + "/blub_frame_00" + std::to_string(k) + ".obj");
    ASSERT_EQ(frame.vertex_count(), swim_model().model().mesh().vertex_count());
    EXPECT_EQ(frame.indices, swim_model().model().mesh().indices);
    double largest = 0.0;
    for (std::size_t v = 0; v < frame.vertex_count(); ++v) {
      largest =
          std::max(largest, double(glm::length(frame.positions[v] - baked.batch.position(k, v))));
    }
    EXPECT_LT(largest, 1e-6);
  }
  EXPECT_FALSE(fs::exists(folder + "/blub_frame_004.obj"));
}

}  // namespace
}  // namespace finflex::bake
