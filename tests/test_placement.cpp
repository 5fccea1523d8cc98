// World placement (finflex/placement.hpp): the convention (the body frame's origin at
// `position`, its axes turned by `orientation`, its length scaled to `length`), the
// kernels against the reference with placements from the host and from a device
// buffer, and bad placements named.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

constexpr float kPi = 3.14159265f;

Placement placed(glm::vec3 position, float yaw, float pitch, float length) {
  Placement p;
  p.position = position;
  p.orientation =
      glm::angleAxis(yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(pitch, glm::vec3(0, 0, 1));
  p.length = length;
  return p;
}

TEST(Placement, TheBodyFrameGoesWhereThePlacementSays) {
  // The real Blub (head at mesh +z, length about 2.9 mesh units) straight, placed 1 m
  // long, heading along world -z (yaw 90 degrees), at (2, 0.5, -1).
  const Mesh mesh = load_mesh(test::data_path("blub/fish_low_resolution.obj"));
  const BodyFrame body = find_body_frame(mesh);
  const RiggedMesh model = RiggedMesh::single_bend(mesh, body, BendMode::kExact);
  const Placement where = placed({2.0f, 0.5f, -1.0f}, 0.5f * kPi, 0.0f, 1.0f);
  ReferenceJob job;
  const RigParameters straight(model, 1);
  DeformedBatch<double> out;
  job.instances = straight.instance_count();
  job.parameters = straight.view();
  job.placements = &where;
  job.outputs = &out;
  run_reference(model, job);
  double lowest = 1e9, highest = -1e9;
  glm::dvec3 centroid(0.0);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const glm::dvec3 p = out.position(0, v);
    // Yaw 90 degrees turns e_x (the head) to world -z.
    lowest = std::min(lowest, -p.z);
    highest = std::max(highest, -p.z);
    centroid += p;
    // The body's right side (e_z) is world +x: its extent is the fish's width.
    const glm::dvec3 rest_local = body.point_to_local(glm::dvec3(mesh.positions[v]));
    EXPECT_NEAR(p.x - 2.0, rest_local.z * 1.0, 1e-9);
    EXPECT_NEAR(p.y - 0.5, rest_local.y * 1.0, 1e-9);
    // Normals turn with it, unscaled.
    EXPECT_NEAR(glm::length(out.normal(0, v)), 1.0, 1e-9);
  }
  EXPECT_NEAR(highest - lowest, 1.0, 1e-9);  // the body's length is the placed length
  // The pivot (the body frame's origin, the surface centroid) is at the position.
  const glm::dvec3 origin_world = glm::dvec3(2.0, 0.5, -1.0);
  EXPECT_LT(glm::length(place_point(placement_record(where), glm::dvec3(0.0)) - origin_world),
            1e-6);
  // The record places body-local coordinates: the snout's, (2), lands where the
  // reference put it.
  std::size_t snout = 0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (body.point_to_local(glm::dvec3(mesh.positions[v])).x >
        body.point_to_local(glm::dvec3(mesh.positions[snout])).x) {
      snout = v;
    }
  }
  const glm::dvec3 snout_local = body.point_to_local(glm::dvec3(mesh.positions[snout]));
  EXPECT_LT(glm::length(place_point(placement_record(where), snout_local) - out.position(0, snout)),
            1e-6);
}

TEST(Placement, DeviceMatchesTheReferenceFromHostAndDeviceBuffers) {
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const RiggedMesh rigged(
      mesh, resolve_rig(load_rig_file(test::data_path("rigs/barramundi.rig.json")), mesh));
  const RiggedMesh bend = RiggedMesh::single_bend(mesh, find_body_frame(mesh), BendMode::kPaper);
  const std::vector<Placement> where = {placed({0.0f, 0.0f, 0.0f}, 0.0f, 0.0f, 0.3f),
                                        placed({1.5f, 0.7f, -0.4f}, 2.0f, 0.3f, 0.45f),
                                        placed({-1.2f, 0.2f, 1.1f}, -2.6f, -0.2f, 0.38f)};
  for (const RiggedMesh* model : {&bend, &rigged}) {
    RigParameters values(*model, 3);
    for (std::size_t i = 0; i < 3; ++i) {
      for (const RigParameter& p : model->rig().parameters)
        values.values()[i * values.values_per_instance() + p.offset] =
            static_cast<float>(0.3 * double(i + 1) * p.limit);
    }
    ClDeformer deformer(test::shared_context(), *model);
    DeviceBatch batch = deformer.allocate(3);
    for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
      ClJob job;
      job.instances = values.instance_count();
      job.parameters = values.view();
      job.normals = normals;
      job.placements = where.data();
      job.outputs = &batch;
      deformer.enqueue(job);
      const DeformedBatch<float> from_host = deformer.read(batch);
      const DeformedBatch<double> reference =
          run_reference(*model, values, normals, false, where.data());
      const AccuracyReport report =
          compare_to_reference(*model, values.view(), normals, from_host, reference, where.data());
      SCOPED_TRACE(std::string(model == &bend ? "bend " : "rig ") + to_string(normals));
      EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
      EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;

      // The same records written to a buffer of the caller's.
      std::vector<float> records;
      for (const Placement& p : where) {
        const PlacementRecord r = placement_record(p);
        records.insert(records.end(), r.begin(), r.end());
      }
      cl::Buffer buffer(test::shared_context().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                        records.size() * sizeof(float), records.data());
      job.placements = nullptr;
      job.device.placements = &buffer;
      deformer.enqueue(job);
      const DeformedBatch<float> from_buffer = deformer.read(batch);
      EXPECT_EQ(from_buffer.positions, from_host.positions);
      EXPECT_EQ(from_buffer.normals, from_host.normals);
    }
  }
}

TEST(Placement, ARootWithoutStagesIsPlacedFromMeshCoordinates) {
  // The last stage of every path is the tail's, in its own frame: the kernels place
  // from mesh coordinates through the root frame's row of the stage table.
  const Mesh mesh = load_mesh(test::data_path("barramundi/BarramundiFish.gltf"));
  const RigSpec spec = parse_rig_json(R"({
    "components": [
      {"name": "body", "select": "all", "chain": []},
      {"name": "tail", "parent": "body",
       "select": {"box": {"min": [-1, -1, -1], "max": [-0.2, 1, 1]}},
       "chain": [{"deformer": "bend", "mode": "exact", "param": "tail_m"},
                 {"deformer": "hinge", "param": "tail_angle", "width": 0.3}]}]})");
  const RiggedMesh model(mesh, resolve_rig(spec, mesh));
  ASSERT_TRUE(model.rig().components.front().chain.empty());
  const std::vector<Placement> where = {placed({1.5f, 0.7f, -0.4f}, 2.0f, 0.3f, 0.45f),
                                        placed({-1.2f, 0.2f, 1.1f}, -2.6f, -0.2f, 0.38f)};
  RigParameters values(model, 2);
  for (std::size_t i = 0; i < 2; ++i) {
    for (const RigParameter& p : model.rig().parameters)
      values.values()[i * values.values_per_instance() + p.offset] =
          static_cast<float>(0.4 * double(i + 1) * p.limit);
  }
  ReferenceJob reference_job;
  DeformedBatch<double> reference;
  reference_job.instances = values.instance_count();
  reference_job.parameters = values.view();
  reference_job.placements = where.data();
  reference_job.outputs = &reference;
  run_reference(model, reference_job);
  ClDeformer deformer(test::shared_context(), model);
  DeviceBatch batch = deformer.allocate(2);
  for (RigPath path : {RigPath::kFused, RigPath::kPasses}) {
    ClJob job;
    job.instances = values.instance_count();
    job.parameters = values.view();
    job.path = path;
    job.placements = where.data();
    job.outputs = &batch;
    deformer.enqueue(job);
    const AccuracyReport report = compare_to_reference(
        model, values.view(), job.normals, deformer.read(batch), reference, where.data());
    SCOPED_TRACE(path == RigPath::kFused ? "fused" : "passes");
    EXPECT_LE(report.max_position_ratio, 1.0) << report.max_position_error;
    EXPECT_LE(report.max_normal_ratio, 1.0) << report.max_normal_error;
  }
}

TEST(Placement, BadPlacementsAreNamed) {
  const RiggedMesh model =
      RiggedMesh::single_bend(test::synthetic_fish(8, 8), BodyFrame::identity(), BendMode::kPaper);
  ClDeformer deformer(test::shared_context(), model);
  DeviceBatch batch = deformer.allocate(2);
  const RigParameters values(model, 2);
  std::vector<Placement> where(2);
  where[1].length = -1.0f;
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.placements = where.data();
  job.outputs = &batch;
  auto field_of = [&] {
    try {
      deformer.enqueue(job);
    } catch (const Error& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(field_of(), "job.placements[1]");
  where[1].length = 1.0f;
  where[1].orientation = glm::quat(2.0f, 0.0f, 0.0f, 0.0f);
  EXPECT_EQ(field_of(), "job.placements[1]");
  where[1].orientation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  where[1].position.y = NAN;
  EXPECT_EQ(field_of(), "job.placements[1]");
  where[1].position.y = 0.0f;
  EXPECT_EQ(field_of(), "accepted");
  cl::Buffer buffer(test::shared_context().context(), CL_MEM_READ_ONLY, 64 * sizeof(float));
  job.device.placements = &buffer;
  EXPECT_EQ(field_of(), "job.placements");  // both given
}

}  // namespace
}  // namespace finflex
