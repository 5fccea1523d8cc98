// Deforming only the instances a list on the device names (ClJob::list) and a species
// at its levels (finflex/level_deformer.hpp): each listed row bit for bit the full
// batch's instance, on every kernel (fused, passes, single bend); each level's rows the
// level's full deformation of the instances its list holds; the rows the lists leave
// alone untouched; bad input named, nothing enqueued.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/test_support.hpp"
#include "support/throws_error.hpp"

namespace finflex {
namespace {

RiggedMesh swim_model(const std::string& mesh_file, const std::string& rig_file) {
  Mesh mesh = load_mesh(test::data_path(mesh_file));
  compute_vertex_normals(mesh);
  return RiggedMesh(mesh, resolve_rig(load_rig_file(test::data_path(rig_file)), mesh));
}

const RiggedMesh& barramundi() {
  static const RiggedMesh model =
      swim_model("barramundi/BarramundiFish.gltf", "rigs/barramundi_swim.rig.json");
  return model;
}

template <typename T>
cl::Buffer upload(const std::vector<T>& values) {
  Context& context = test::shared_context();
  const std::size_t bytes = values.size() * sizeof(T);
  cl::Buffer buffer(context.context(), CL_MEM_READ_WRITE, bytes);
  check_cl(context.queue().enqueueWriteBuffer(buffer, CL_TRUE, 0, bytes, values.data()),
           "clEnqueueWriteBuffer");
  return buffer;
}

std::vector<float> rows_of(const RigParameters& values) {
  const ParameterView view = values.view();
  return std::vector<float>(view.data, view.data + view.instance_count * view.stride);
}

// Fish in front of a camera at the origin looking down -z, from 0.5 m to 40 m away.
std::vector<PlacementRecord> fish_ahead(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> x(-12.0f, 12.0f), y(-3.0f, 3.0f), z(-40.0f, -0.5f);
  std::uniform_real_distribution<float> angle(0.0f, 6.2831853f), length(0.3f, 0.5f);
  std::vector<PlacementRecord> out;
  for (std::size_t i = 0; i < count; ++i) {
    Placement p;
    p.position = glm::vec3(x(random), y(random), z(random));
    p.orientation = glm::quat(glm::vec3(0.2f * angle(random), angle(random), 0.0f));
    p.length = length(random);
    out.push_back(placement_record(p));
  }
  return out;
}

// Every position and normal of row `row` of `got` equal, bit for bit, to instance
// `instance` of `want`.
void expect_row_is_instance(const DeformedBatch<float>& got, std::size_t row,
                            const DeformedBatch<float>& want, std::size_t instance,
                            std::size_t vertices) {
  for (std::size_t v = 0; v < vertices; ++v) {
    ASSERT_EQ(got.position(row, v), want.position(instance, v))
        << "row " << row << " (instance " << instance << "), vertex " << v;
    ASSERT_EQ(got.normal(row, v), want.normal(instance, v))
        << "row " << row << " (instance " << instance << "), vertex " << v;
  }
}

struct Listed {
  ClJob job;
  cl::Buffer entries, counts;
};

// A job over `rows` rows of `outputs` listing `entries`, `count` of them read.
void set_list(Listed& listed, const std::vector<cl_uint>& entries, cl_uint count, std::size_t first,
              std::size_t sources) {
  listed.entries = upload(entries);
  listed.counts = upload(std::vector<cl_uint>{7, count});
  listed.job.list = {&listed.entries, first, &listed.counts, 1, sources};
}

void check_listed_rows(const RiggedMesh& model, RigPath path) {
  Context& context = test::shared_context();
  ClDeformer deformer(context, model);
  const std::size_t sources = 12;
  std::vector<double> fractions;
  for (std::size_t i = 0; i < sources; ++i) fractions.push_back(-1.0 + 2.0 * double(i) / 11.0);
  const RigParameters values = test::at_fractions_of_the_limits(model, fractions);
  const cl::Buffer parameters = upload(rows_of(values));
  const cl::Buffer placements = upload(fish_ahead(sources, 3));

  DeviceBatch full = deformer.allocate(sources);
  ClJob job;
  job.instances = sources;
  job.path = path;
  job.outputs = &full;
  job.device.parameters = &parameters;
  job.device.placements = &placements;
  deformer.enqueue(job);
  const DeformedBatch<float> want = deformer.read(full);

  // First every row its own instance, then a list that repeats one, names one past the
  // inputs (skipped) and leaves the last rows out.
  const std::size_t rows = 8;
  DeviceBatch batch = deformer.allocate(rows);
  Listed listed;
  listed.job = job;
  listed.job.instances = rows;
  listed.job.outputs = &batch;
  set_list(listed, {0, 1, 2, 3, 4, 5, 6, 7}, 8, 0, sources);
  deformer.enqueue(listed.job);
  set_list(listed, {99, 9, 3, 3, 11, 0, 12, 5, 2}, 6, 1, sources);
  deformer.enqueue(listed.job);
  const DeformedBatch<float> got = deformer.read(batch);
  const std::vector<std::size_t> row_holds = {9, 3, 3, 11, 0, 5, 6, 7};
  for (std::size_t row = 0; row < rows; ++row)
    expect_row_is_instance(got, row, want, row_holds[row], model.vertex_count());
}

TEST(ListedInstances, EachRowIsItsInstanceOfTheFullBatchOnTheFusedPath) {
  check_listed_rows(barramundi(), RigPath::kFused);
}

TEST(ListedInstances, EachRowIsItsInstanceOfTheFullBatchOnThePasses) {
  check_listed_rows(barramundi(), RigPath::kPasses);
}

TEST(ListedInstances, EachRowIsItsInstanceOfTheFullBatchOnTheSingleBend) {
  Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  compute_vertex_normals(mesh);
  const RiggedMesh model = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kExact);
  check_listed_rows(model, RigPath::kAuto);
}

TEST(ListedInstances, BadListsAreNamedAndNothingIsEnqueued) {
  Context& context = test::shared_context();
  ClDeformer deformer(context, barramundi());
  const RigParameters values = test::at_fractions_of_the_limits(barramundi(), {0.5, -0.5});
  const cl::Buffer parameters = upload(rows_of(values));
  const cl::Buffer placements = upload(fish_ahead(2, 1));
  DeviceBatch batch = deformer.allocate(4);
  Listed listed;
  listed.job.instances = 4;
  listed.job.outputs = &batch;
  listed.job.device.parameters = &parameters;
  listed.job.device.placements = &placements;
  set_list(listed, {0, 1, 0, 1}, 4, 0, 2);
  EXPECT_NO_THROW(deformer.check(listed.job));

  const auto fails = [&](ClJob job, const std::string& field, const std::string& part) {
    return test::ThrowsError([&] { deformer.enqueue(job); }, ErrorCode::kInvalidArgument, field,
                             part);
  };
  ClJob job = listed.job;
  const RigParameters four = test::at_fractions_of_the_limits(barramundi(), {0.5, -0.5, 0.1, 0.2});
  job.device.parameters = nullptr;
  job.parameters = four.view();
  EXPECT_TRUE(fails(job, "job.list", "job.device.parameters"));
  job = listed.job;
  job.list.counts = nullptr;
  EXPECT_TRUE(fails(job, "job.list.counts", "null"));
  job = listed.job;
  job.list.sources = 0;
  EXPECT_TRUE(fails(job, "job.list.sources", "0"));
  job = listed.job;
  job.list.first = 1;  // 1 + 4 entries: the buffer holds 4
  EXPECT_TRUE(fails(job, "job.list.entries", "5 cl_uint"));
  job = listed.job;
  job.list.count_index = 2;
  EXPECT_TRUE(fails(job, "job.list.counts", "3 cl_uint"));
}

// ---- A species at its levels

const DetailLevels& barramundi_levels() {
  static const DetailLevels levels = make_detail_levels(barramundi(), LevelOptions{});
  return levels;
}

LevelView camera() {
  return LevelView::look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 50.0, 640, 360, 0.1, 30.0);
}

TEST(LevelDeformer, EachLevelsRowsAreItsListsInstancesDeformedAtThatLevel) {
  Context& context = test::shared_context();
  const std::size_t fish = 300;
  std::vector<double> fractions;
  for (std::size_t i = 0; i < fish; ++i) fractions.push_back(std::sin(0.37 * double(i)));
  const RigParameters values = test::at_fractions_of_the_limits(barramundi(), fractions);
  const cl::Buffer parameters = upload(rows_of(values));
  const cl::Buffer placements = upload(fish_ahead(fish, 11));
  const DetailLevels& levels = barramundi_levels();
  LevelChoiceOptions options;
  options.level_rows = {40, 120, 300, 300};  // the finest levels too small for some
  LevelDeformer species(context, levels, fish, options);
  ClDeviceInputs inputs;
  inputs.parameters = &parameters;
  inputs.placements = &placements;
  std::vector<cl::Event> kernels;
  species.enqueue(inputs, fish, {camera()}, NormalMode::kRotate, nullptr, &kernels);
  EXPECT_GE(kernels.size(), 3 + levels.size());
  const LevelChooser::Choice choice = species.chooser().read();

  std::size_t listed = 0;
  for (std::size_t k = 0; k < levels.size(); ++k) {
    ClDeformer full_deformer(context, levels.level(k).model);
    DeviceBatch full = full_deformer.allocate(fish);
    ClJob job;
    job.instances = fish;
    job.outputs = &full;
    job.device = inputs;
    full_deformer.enqueue(job);
    const DeformedBatch<float> want = full_deformer.read(full);
    const DeformedBatch<float> got = species.deformer(k).read(species.batch(k));
    const std::vector<std::uint32_t>& list = choice.lists[k];
    ASSERT_LE(list.size(), species.chooser().rows(k));
    EXPECT_EQ(choice.draw_arguments[5 * k + 1], list.size());
    EXPECT_EQ(choice.draw_arguments[5 * k], levels.level(k).triangle_count * 3);
    for (std::size_t row = 0; row < list.size(); ++row) {
      // Drawn at its level or, for want of rows, a coarser one.
      ASSERT_GE(int(k), choice.level_of[list[row]]);
      expect_row_is_instance(got, row, want, list[row], levels.level(k).model.vertex_count());
    }
    listed += list.size();
  }
  std::size_t visible = 0;
  for (int level : choice.level_of) visible += level >= 0 ? 1 : 0;
  EXPECT_GT(visible, 100u);
  EXPECT_EQ(listed + choice.undrawn, visible);
}

TEST(LevelDeformer, TheSameFrameGivesTheSameRowsBitForBit) {
  Context& context = test::shared_context();
  const std::size_t fish = 64;
  const RigParameters values =
      test::at_fractions_of_the_limits(barramundi(), std::vector<double>(fish, 0.6));
  const cl::Buffer parameters = upload(rows_of(values));
  const cl::Buffer placements = upload(fish_ahead(fish, 5));
  ClDeviceInputs inputs;
  inputs.parameters = &parameters;
  inputs.placements = &placements;
  // The rows each list fills, as bits: positions and normals, level by level.
  std::vector<std::vector<float>> runs;
  std::vector<LevelChooser::Choice> choices;
  for (int run = 0; run < 2; ++run) {
    LevelDeformer species(context, barramundi_levels(), fish);
    species.enqueue(inputs, fish, {camera()});
    choices.push_back(species.chooser().read());
    runs.emplace_back();
    for (std::size_t k = 0; k < species.level_count(); ++k) {
      const DeformedBatch<float> rows = species.deformer(k).read(species.batch(k));
      for (std::size_t row = 0; row < choices.back().lists[k].size(); ++row) {
        for (std::size_t v = 0; v < species.deformer(k).model().vertex_count(); ++v) {
          for (int c = 0; c < 3; ++c) {
            runs.back().push_back(rows.position(row, v)[c]);
            runs.back().push_back(rows.normal(row, v)[c]);
          }
        }
      }
    }
  }
  EXPECT_EQ(choices[1].lists, choices[0].lists);
  EXPECT_GT(runs[0].size(), 0u);
  EXPECT_EQ(std::memcmp(runs[0].data(), runs[1].data(), runs[0].size() * sizeof(float)), 0);
  EXPECT_EQ(runs[1].size(), runs[0].size());
}

TEST(LevelDeformer, MissingInputsAndForeignBatchesAreNamed) {
  Context& context = test::shared_context();
  LevelDeformer species(context, barramundi_levels(), 8);
  const cl::Buffer placements = upload(fish_ahead(8, 2));
  ClDeviceInputs inputs;
  inputs.placements = &placements;
  EXPECT_TRUE(test::ThrowsError([&] { species.enqueue(inputs, 8, {camera()}); },
                                ErrorCode::kInvalidArgument, "inputs.parameters", "null"));
  const RigParameters values =
      test::at_fractions_of_the_limits(barramundi(), std::vector<double>(8, 0.1));
  const cl::Buffer parameters = upload(rows_of(values));
  inputs = {};
  inputs.parameters = &parameters;
  EXPECT_TRUE(test::ThrowsError([&] { species.enqueue(inputs, 8, {camera()}); },
                                ErrorCode::kInvalidArgument, "inputs.placements", "null"));
  EXPECT_TRUE(test::ThrowsError([&] { species.set_batch(1, species.deformer(0).allocate(8)); },
                                ErrorCode::kInvalidArgument, "batch", "level 1"));
  EXPECT_TRUE(test::ThrowsError([&] { species.set_batch(0, species.deformer(0).allocate(7)); },
                                ErrorCode::kInvalidArgument, "batch", "holds 7"));
}

}  // namespace
}  // namespace finflex
