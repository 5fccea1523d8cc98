// Geometric properties of the OpenCL output itself: the spine's arc length, normals
// that agree with the deformed mesh's own faces, and a body frame that moves with
// the fish (a rigidly moved fish bends into the rigidly moved shape); the hinge's
// geometry (untouched behind its base, arc length kept through the ramp, a rigid turn
// by its angle past it, towards +z for a positive angle) on the kernels' output.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

// The whole-body bend of `mesh` in `frame` with one instance per entry of m.
DeformedBatch<float> bend_on_device(const Mesh& mesh, const BodyFrame& frame,
                                    const std::vector<float>& m, BendMode mode,
                                    NormalMode normals) {
  const RiggedMesh model = RiggedMesh::single_bend(mesh, frame, mode);
  ClDeformer deformer(test::shared_context(), model);
  return test::run_on_device(deformer, test::values_of(model, m), normals);
}

double spine_length(const DeformedBatch<float>& batch, std::size_t instance, int samples) {
  double length = 0.0;
  for (int i = 1; i < samples; ++i) {
    length += glm::length(glm::dvec3(batch.position(instance, static_cast<std::size_t>(i))) -
                          glm::dvec3(batch.position(instance, static_cast<std::size_t>(i - 1))));
  }
  return length;
}

TEST(Geometry, ExactBendKeepsTheSpineArcLength) {
  const int samples = 4001;
  const std::vector<float> m = {0.25f, -0.5f, 0.8f, -0.95f};  // 2 m x_max = |m|
  const DeformedBatch<float> bent =
      bend_on_device(test::spine_ribbon(samples, 0.5), BodyFrame::identity(), m, BendMode::kExact,
                     NormalMode::kRotate);
  for (std::size_t i = 0; i < m.size(); ++i) {
    EXPECT_LT(std::fabs(spine_length(bent, i, samples) - 1.0), 1e-5) << "m = " << m[i];
  }
}

TEST(Geometry, PaperBendShowsTheSeriesError) {
  // METHOD.md section 5: about 1 % (0.96 %) at 2 m x_max = 1, 0.25 % at 0.8.
  const int samples = 4001;
  const DeformedBatch<float> bent =
      bend_on_device(test::spine_ribbon(samples, 0.5), BodyFrame::identity(), {1.0f, 0.8f},
                     BendMode::kPaper, NormalMode::kRotate);
  EXPECT_NEAR(spine_length(bent, 0, samples) - 1.0, 9.6e-3, 0.4e-3);
  EXPECT_NEAR(spine_length(bent, 1, samples) - 1.0, 2.5e-3, 0.3e-3);
}

TEST(Geometry, NormalsAgreeWithTheDeformedFaces) {
  for (const char* fish : test::kBundledFish) {
    // Rest normals recomputed from the faces, so only the deformation is measured
    // (scanned normals do not match the faces exactly to begin with).
    Mesh rest = load_mesh(test::data_path(fish));
    compute_vertex_normals(rest);
    const BodyFrame frame = find_body_frame(rest);
    const double limit = test::bend_limit(RiggedMesh::single_bend(rest, frame, BendMode::kExact));
    const std::vector<float> m = {static_cast<float>(0.8 * limit)};
    for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
      const double rotate = mean_angle_to_face_normals(
          instance_mesh(rest, bend_on_device(rest, frame, m, mode, NormalMode::kRotate), 0));
      const double jacobian = mean_angle_to_face_normals(
          instance_mesh(rest, bend_on_device(rest, frame, m, mode, NormalMode::kJacobian), 0));
      SCOPED_TRACE(std::string(fish) + " " + to_string(mode));
      // Measured (docs/accuracy.md): jacobian 0.04-0.24 degrees, rotate 0.8-2.5 degrees;
      // jacobian is 3x (barramundi, coarse fins) to 55x (blub) closer to the faces.
      const double degree = 3.14159265358979 / 180.0;
      EXPECT_LT(jacobian, 0.5 * rotate);
      EXPECT_LT(jacobian, 0.3 * degree);
      EXPECT_LT(rotate, 3.0 * degree);
    }
  }
}

// Rotate-mode normals are rotated, not renormalised: they must stay unit on real
// fish, for the single bend and through a rig's chained stages, at every parameter.
TEST(Geometry, RotatedNormalsStayUnit) {
  const Mesh mesh = load_mesh(test::data_path("blub/fish.obj"));
  const BodyFrame frame = find_body_frame(mesh);
  const double limit = test::bend_limit(RiggedMesh::single_bend(mesh, frame, BendMode::kExact));
  std::vector<float> m;
  for (double f : {-1.0, -0.5, 0.0, 0.3, 0.9, 1.0}) m.push_back(static_cast<float>(f * limit));
  double worst = 0.0;
  for (BendMode mode : {BendMode::kPaper, BendMode::kExact}) {
    const DeformedBatch<float> bent = bend_on_device(mesh, frame, m, mode, NormalMode::kRotate);
    for (std::size_t i = 0; i < m.size(); ++i) {
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        worst = std::max(worst, std::fabs(glm::length(glm::dvec3(bent.normal(i, v))) - 1.0));
    }
  }
  const RiggedMesh model(mesh,
                         resolve_rig(load_rig_file(test::data_path("rigs/blub.rig.json")), mesh));
  ClDeformer deformer(test::shared_context(), model);
  RigParameters values(model, 3);
  const std::vector<RigParameter>& parameters = model.rig().parameters;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t p = 0; p < parameters.size(); ++p)
      values.values()[i * values.values_per_instance() + parameters[p].offset] =
          static_cast<float>((i == 0 ? -1.0 : 0.45 * double(i)) * parameters[p].limit);
  }
  const DeformedBatch<float> rigged =
      test::run_on_device(deformer, values, NormalMode::kRotate, RigPath::kFused);
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      worst = std::max(worst, std::fabs(glm::length(glm::dvec3(rigged.normal(i, v))) - 1.0));
  }
  EXPECT_LT(worst, 2e-6);
}

TEST(Geometry, FoldOverIsCountedWhereTheRadiusOfCurvatureIsShorterThanZ) {
  // A vertex at height z above the spine folds where z k >= 1, k = 2m / sqrt(1 - 4m^2x^2).
  Mesh mesh = test::spine_ribbon(101, 0.5);
  for (glm::vec3& p : mesh.positions) p.z = 0.25f;  // the ribbon lifted off the secant plane
  const RiggedMesh exact = RiggedMesh::single_bend(mesh, BodyFrame::identity(), BendMode::kExact);
  const RiggedMesh paper = RiggedMesh::single_bend(mesh, BodyFrame::identity(), BendMode::kPaper);
  const RigParameters m = test::values_of(exact, {0.0f, -1.0f, 1.0f});
  EXPECT_EQ(count_folded_vertices(exact, m.view(), 0), 0u);
  EXPECT_EQ(count_folded_vertices(exact, m.view(), 1), 0u);  // bends away from z > 0
  // m = 1: z k = 0.5 / sqrt(1 - 4x^2) >= 1 for |x| >= sqrt(3)/4 = 0.433: x = +-0.44 .. +-0.5.
  EXPECT_EQ(count_folded_vertices(exact, m.view(), 2), 2u * 2u * 7u);
  EXPECT_EQ(count_folded_vertices(paper, m.view(), 2), 0u);  // the series' k < 4m
}

TEST(Geometry, RigidlyMovedFishBendsIntoTheMovedShape) {
  for (const char* fish : test::kBundledFish) {
    const Mesh mesh = load_mesh(test::data_path(fish));
    const BodyFrame frame = find_body_frame(mesh);
    const glm::dmat4 motion =
        glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(12.0, -3.0, 7.5)), 2.1,
                    glm::normalize(glm::dvec3(0.3, -0.8, 0.5)));
    Mesh moved = mesh;
    for (glm::vec3& p : moved.positions) p = glm::vec3(motion * glm::dvec4(glm::dvec3(p), 1.0));
    for (glm::vec3& n : moved.normals) n = glm::vec3(motion * glm::dvec4(glm::dvec3(n), 0.0));
    for (glm::vec4& t : moved.tangents)
      t = glm::vec4(glm::vec3(motion * glm::dvec4(glm::dvec3(t), 0.0)), t.w);

    const double limit = test::bend_limit(RiggedMesh::single_bend(mesh, frame, BendMode::kExact));
    const std::vector<float> m = {static_cast<float>(0.7 * limit)};
    const DeformedBatch<float> original =
        bend_on_device(mesh, frame, m, BendMode::kExact, NormalMode::kJacobian);
    const DeformedBatch<float> bent_moved =
        bend_on_device(moved, find_body_frame(moved), m, BendMode::kExact, NormalMode::kJacobian);
    double position_error = 0.0, normal_error = 0.0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::dvec3 expected =
          glm::dvec3(motion * glm::dvec4(glm::dvec3(original.position(0, v)), 1.0));
      const glm::dvec3 expected_normal =
          glm::dvec3(motion * glm::dvec4(glm::dvec3(original.normal(0, v)), 0.0));
      position_error =
          std::max(position_error, glm::length(glm::dvec3(bent_moved.position(0, v)) - expected));
      normal_error = std::max(normal_error,
                              glm::length(glm::dvec3(bent_moved.normal(0, v)) - expected_normal));
    }
    SCOPED_TRACE(fish);
    EXPECT_LT(position_error, 2e-5 * (frame.length + 20.0));
    EXPECT_LT(normal_error, 1e-4);
  }
}

// ---------------------------------------------------------------------------------
// The hinge on the device

// A rig of one hinge of `width` reading "angle", in the identity frame.
RiggedMesh hinge_model(const Mesh& mesh, double width) {
  RigSpec spec;
  spec.frame.mode = FrameSpec::Mode::kIdentity;
  ComponentSpec body;
  body.name = "body";
  StageSpec hinge = make_stage("hinge", "angle");
  set_option(hinge, "width", width);
  body.chain.push_back(hinge);
  spec.components.push_back(body);
  return RiggedMesh(mesh, resolve_rig(spec, mesh));
}

// The hinge's outputs on the device, one instance per angle (the paths and dispatches
// agree with each other and with the reference on rigs with hinges:
// tests/test_rig_deformer.cpp).
DeformedBatch<float> hinge_on_device(const RiggedMesh& model, const std::vector<float>& angles,
                                     NormalMode normals) {
  ClDeformer deformer(test::shared_context(), model);
  return test::run_on_device(deformer, test::values_of(model, angles), normals);
}

glm::dvec3 turned(const glm::dvec3& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x - s * v.z, v.y, s * v.x + c * v.z};
}

const double kPi = 3.14159265358979323846;

TEST(Geometry, HingeKeepsTheSpineArcLengthThroughTheRamp) {
  // The spine from x = -0.5 to 0.5 through a ramp of width 0.4 (its arc of radius
  // 0.4 / |angle|), at angles up to the limit pi: its length stays 1. Float32 chords
  // of 1/4000: measured within 7e-8 of it; bound 1e-6.
  const int samples = 4001;
  const RiggedMesh model = hinge_model(test::spine_ribbon(samples, 0.5), 0.4);
  const std::vector<float> angles = {0.5f, -1.5f, 2.5f, static_cast<float>(kPi),
                                     -static_cast<float>(kPi)};
  ASSERT_FLOAT_EQ(static_cast<float>(model.rig().parameters[0].limit), static_cast<float>(kPi));
  {
    const DeformedBatch<float> bent = hinge_on_device(model, angles, NormalMode::kRotate);
    for (std::size_t i = 0; i < angles.size(); ++i) {
      EXPECT_LT(std::fabs(spine_length(bent, i, samples) - 1.0), 1e-6) << "angle " << angles[i];
      // The spine's end: the ramp's end (r sin a, 0, r (1 - cos a)), r = 0.4 / a, then
      // 0.1 along the turned spine.
      const double a = angles[i], r = 0.4 / a;
      const glm::dvec3 end =
          glm::dvec3(r * std::sin(a), 0.0, r * (1.0 - std::cos(a))) + turned({0.1, 0, 0}, a);
      EXPECT_LT(glm::length(glm::dvec3(bent.position(i, samples - 1)) - end), 2e-6)
          << "angle " << a;
    }
  }
}

TEST(Geometry, HingeTurnsItsPartRigidlyAndLeavesTheRestUntouched) {
  // On the synthetic fish (x in [-0.5, 0.5]) with its base at x = 0: behind it (x <=
  // 0) every vertex keeps its position, normal and tangent; past the ramp (x >= 0.15)
  // the part turns as one body by the angle about e_y, towards +z for a positive one:
  // p' = f(width) + R (p - (width, 0, 0)), normals and tangents by R.
  const Mesh mesh = test::synthetic_fish(48, 24, true);
  const double width = 0.15;
  const RiggedMesh model = hinge_model(mesh, width);
  const std::vector<float> angles = {0.8f, -2.2f, static_cast<float>(kPi)};
  for (NormalMode normals : {NormalMode::kRotate, NormalMode::kJacobian}) {
    {
      const DeformedBatch<float> bent = hinge_on_device(model, angles, normals);
      double untouched = 0.0, untouched_directions = 0.0, turned_error = 0.0,
             turned_directions = 0.0;
      std::size_t behind = 0, past = 0;
      for (std::size_t i = 0; i < angles.size(); ++i) {
        const double a = angles[i], r = width / a;
        const glm::dvec3 ramp_end(r * std::sin(a), 0.0, r * (1.0 - std::cos(a)));
        for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
          const glm::dvec3 p(mesh.positions[v]);
          const glm::dvec3 n = glm::normalize(glm::dvec3(mesh.normals[v]));
          const glm::dvec3 t(glm::vec3(mesh.tangents[v]));
          const glm::dvec3 got(bent.position(i, v));
          const double normal_error_rest = glm::length(glm::dvec3(bent.normal(i, v)) - n);
          if (p.x <= 0.0) {
            ++behind;
            untouched = std::max(untouched, glm::length(got - p));
            untouched_directions =
                std::max({untouched_directions, normal_error_rest,
                          glm::length(glm::dvec3(bent.tangent(i, v)) - glm::normalize(t))});
          } else if (p.x >= width) {
            ++past;
            const glm::dvec3 expected = ramp_end + turned(p - glm::dvec3(width, 0.0, 0.0), a);
            turned_error = std::max(turned_error, glm::length(got - expected));
            turned_directions = std::max(
                {turned_directions, glm::length(glm::dvec3(bent.normal(i, v)) - turned(n, a)),
                 glm::length(glm::dvec3(bent.tangent(i, v)) - turned(glm::normalize(t), a))});
            if (a > 0.0 && a < kPi && p.x > 0.3) {
              ASSERT_GT(got.z, p.z) << "a positive angle turns towards +z, vertex " << v;
            }
          }
        }
      }
      SCOPED_TRACE(to_string(normals));
      EXPECT_GT(behind, mesh.vertex_count());
      EXPECT_GT(past, mesh.vertex_count());
      // finflex/accuracy.hpp's bounds for one stage on coordinates of size 1 (measured:
      // 0 and 1.4e-7 behind the base, 6e-8 and 2.2e-7 past the ramp).
      EXPECT_LT(untouched, 2e-6);
      EXPECT_LT(untouched_directions, 2e-6);
      EXPECT_LT(turned_error, 4e-6);
      EXPECT_LT(turned_directions, 2e-5);
    }
  }
}

}  // namespace
}  // namespace finflex
