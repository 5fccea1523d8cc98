// The double-precision reference against the geometry it must have: identity at m = 0,
// mirror symmetry in m, the spine's arc length, the paper's series error, and the
// rotation (8) taking e_z to the secant normal (not the printed, transposed (9)); the
// hinge against its own geometry: untouched behind its base, a circular ramp that
// keeps the spine's length, a rigid turn by its angle past the ramp, towards +z for a
// positive angle.
#include <cmath>

#include <gtest/gtest.h>

#include "finflex/finflex.hpp"
#include "support/deform.hpp"
#include "support/synthetic_fish.hpp"

namespace finflex {
namespace {

const BendMode kModes[] = {BendMode::kPaper, BendMode::kExact};
const NormalMode kNormalModes[] = {NormalMode::kRotate, NormalMode::kJacobian};

// The bend of one vertex in its frame, as the reference applies it (apply_stage with
// the registry's bend).
LocalVertex bend_local_vertex(const LocalVertex& rest, double m, BendMode mode,
                              NormalMode normals) {
  StageSpec stage = make_stage("bend", "m");
  set_option(stage, "mode", to_string(mode));
  return apply_stage(*stage.deformer, stage.options, &m, rest, normals);
}

// The whole-body bend of `mesh`, already in its body frame.
RiggedMesh identity_bend(const Mesh& mesh, BendMode mode) {
  return RiggedMesh::single_bend(mesh, BodyFrame::identity(), mode);
}

// Length of the bent spine, sampled densely between -x_max and x_max.
double bent_spine_length(double m, double x_max, BendMode mode) {
  const int samples = 20001;
  double length = 0.0;
  glm::dvec3 previous{};
  for (int i = 0; i < samples; ++i) {
    const double x = -x_max + 2.0 * x_max * i / (samples - 1);
    const LocalVertex bent =
        bend_local_vertex({{x, 0.0, 0.0}, {0.0, 0.0, 1.0}, {}}, m, mode, NormalMode::kRotate);
    if (i > 0) length += glm::length(bent.position - previous);
    previous = bent.position;
  }
  return length;
}

TEST(BendReference, ZeroParameterIsTheIdentity) {
  const Mesh mesh = test::synthetic_fish(24, 16, true);
  for (BendMode mode : kModes) {
    const RiggedMesh model = identity_bend(mesh, mode);
    for (NormalMode normals : kNormalModes) {
      const DeformedBatch<double> out =
          run_reference(model, test::values_of(model, {0.0f}), normals);
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        EXPECT_LT(glm::length(out.position(0, v) - glm::dvec3(mesh.positions[v])), 1e-12);
        EXPECT_LT(glm::length(out.normal(0, v) - glm::normalize(glm::dvec3(mesh.normals[v]))),
                  1e-7);
        EXPECT_LT(glm::length(out.tangent(0, v) - glm::dvec3(glm::vec3(mesh.tangents[v]))), 1e-6);
      }
    }
  }
}

TEST(BendReference, OppositeParametersMirrorInZ) {
  for (BendMode mode : kModes) {
    for (NormalMode normals : kNormalModes) {
      for (double x : {-0.5, -0.2, 0.1, 0.45}) {
        const LocalVertex rest{{x, 0.03, 0.02},
                               glm::normalize(glm::dvec3(0.3, -0.2, 0.9)),
                               glm::normalize(glm::dvec3(0.9, 0.1, -0.3))};
        const LocalVertex mirrored{{x, 0.03, -0.02},
                                   glm::normalize(glm::dvec3(0.3, -0.2, -0.9)),
                                   glm::normalize(glm::dvec3(0.9, 0.1, 0.3))};
        const glm::dvec3 flip(1.0, 1.0, -1.0);
        const LocalVertex a = bend_local_vertex(rest, 0.7, mode, normals);
        const LocalVertex b = bend_local_vertex(mirrored, -0.7, mode, normals);
        EXPECT_LT(glm::length(a.position * flip - b.position), 1e-14);
        EXPECT_LT(glm::length(a.normal * flip - b.normal), 1e-14);
        EXPECT_LT(glm::length(a.tangent * flip - b.tangent), 1e-14);
      }
    }
  }
}

TEST(BendReference, ExactBendKeepsTheSpineArcLength) {
  const double x_max = 0.5;
  for (double ratio : {0.25, 0.5, 0.8, 0.95, 1.0}) {  // 2 m x_max
    const double m = ratio / (2.0 * x_max);
    const double length = bent_spine_length(m, x_max, BendMode::kExact);
    EXPECT_LT(std::fabs(length - 2.0 * x_max) / (2.0 * x_max), 1e-7) << "2 m x_max = " << ratio;
  }
}

TEST(BendReference, PaperSeriesErrorIsAsMeasured) {
  // METHOD.md section 5: 0.01 % at 2 m x_max = 0.5, 0.25 % at 0.8, 0.96 % at 1.0,
  // and the spine tip x' = 0.808 against the exact 0.785.
  const double x_max = 0.5;
  const auto relative_error = [&](double ratio) {
    const double length = bent_spine_length(ratio / (2.0 * x_max), x_max, BendMode::kPaper);
    return (length - 2.0 * x_max) / (2.0 * x_max);
  };
  EXPECT_NEAR(relative_error(0.5), 1.0e-4, 0.5e-4);
  EXPECT_NEAR(relative_error(0.8), 2.5e-3, 0.3e-3);
  EXPECT_NEAR(relative_error(1.0), 9.6e-3, 0.4e-3);
  const LocalVertex tip{{1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {}};
  EXPECT_NEAR(bend_local_vertex(tip, 0.5, BendMode::kPaper, NormalMode::kRotate).position.x, 0.8083,
              1e-3);
  EXPECT_NEAR(bend_local_vertex(tip, 0.5, BendMode::kExact, NormalMode::kRotate).position.x, 0.7854,
              1e-3);
}

TEST(BendReference, SpineFollowsTheParabola) {
  // (12): the spine point at arc length x lies on z = m x^2, for the exact bend exactly.
  for (double x : {-0.4, 0.1, 0.5}) {
    const LocalVertex bent = bend_local_vertex({{x, 0.0, 0.0}, {0.0, 0.0, 1.0}, {}}, 0.9,
                                               BendMode::kExact, NormalMode::kRotate);
    EXPECT_NEAR(bent.position.z, 0.9 * x * x, 1e-15);
    EXPECT_DOUBLE_EQ(bent.position.y, 0.0);
  }
}

TEST(BendReference, RotationTakesEzToTheSecantNormal) {
  // (8) with R taking e_z to n: a rest normal e_z on the secant plane becomes n (17),
  // not (-n_x, -n_y, n_z) as the printed matrix (9) would give.
  const double m = 0.8, x = 0.4;
  const LocalVertex bent = bend_local_vertex({{x, 0.0, 0.0}, {0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}}, m,
                                             BendMode::kPaper, NormalMode::kRotate);
  const double a = 1.0 - 2.0 * m * m * x * x - 2.0 * std::pow(m * x, 4);
  const glm::dvec3 n = glm::normalize(glm::dvec3(-2.0 * m * x, 0.0, a));
  EXPECT_LT(glm::length(bent.normal - n), 1e-14);
  EXPECT_NEAR(glm::dot(bent.tangent, n), 0.0, 1e-14);
  EXPECT_GT(bent.tangent.x, 0.0);
}

TEST(BendReference, JacobianNormalsScaleTheAlongSpineComponent) {
  // METHOD.md section 6: normals by R diag(1 / (1 - z k), 1, 1), k = 2m / sqrt(1 - 4m^2x^2).
  const double m = 0.6, x = 0.3, z = 0.05;
  const glm::dvec3 rest_normal = glm::normalize(glm::dvec3(0.5, 0.2, 0.8));
  const LocalVertex bent =
      bend_local_vertex({{x, 0.0, z}, rest_normal, {}}, m, BendMode::kExact, NormalMode::kJacobian);
  const double c = std::sqrt(1.0 - 4.0 * m * m * x * x), k = 2.0 * m / c;
  const glm::dvec3 scaled(rest_normal.x / (1.0 - z * k), rest_normal.y, rest_normal.z);
  const glm::dvec3 u(-2.0 * m * x, 0.0, c);  // n
  const glm::dvec3 t(c, 0.0, 2.0 * m * x);   // unit spine tangent
  const glm::dvec3 expected =
      glm::normalize(scaled.x * t + scaled.y * glm::dvec3(0, 1, 0) + scaled.z * u);
  EXPECT_LT(glm::length(bent.normal - expected), 1e-14);
}

TEST(BendReference, RejectsBadParameters) {
  const RiggedMesh model = identity_bend(test::synthetic_fish(8, 8), BendMode::kPaper);
  const NormalMode normals = NormalMode::kRotate;
  // No instances: the job names the field.
  ReferenceJob empty;
  DeformedBatch<double> out;
  empty.outputs = &out;
  try {
    run_reference(model, empty);
    FAIL() << "expected an error for a job without instances";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "job.instances");
  }
  EXPECT_THROW(run_reference(model, test::values_of(model, {NAN}), normals), Error);
  EXPECT_THROW(run_reference(model, test::values_of(model, {INFINITY}), normals), Error);
  try {
    run_reference(model, test::values_of(model, {0.1f, 1.5f}), normals);  // x_max = 0.5: |m| <= 1
    FAIL() << "expected an out-of-range error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kOutOfRange);
    EXPECT_EQ(e.field(), "m[1]");
    EXPECT_NE(std::string(e.what()).find("1.5"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("[-1, 1]"), std::string::npos);
  }
  // Clamping brings the value to the limit instead.
  const DeformedBatch<double> clamped =
      run_reference(model, test::values_of(model, {1.5f}), normals, true);
  const DeformedBatch<double> at_limit =
      run_reference(model, test::values_of(model, {1.0f}), normals);
  EXPECT_LT(glm::length(clamped.position(0, 0) - at_limit.position(0, 0)), 1e-6);
}

// ---------------------------------------------------------------------------------
// The hinge (METHOD.md section 6; engine/src/rig/deformers/hinge.cpp): in its frame the
// spine's angle ramps linearly from 0 at x = 0 to `angle` at x = width (a step at 0
// for width 0), |angle| <= pi.

LocalVertex hinge_local_vertex(const LocalVertex& rest, double angle, double width,
                               NormalMode normals) {
  StageSpec stage = make_stage("hinge", "angle");
  set_option(stage, "width", width);
  return apply_stage(*stage.deformer, stage.options, &angle, rest, normals);
}

// The rotation about e_y by `angle` that takes e_x to (cos, 0, sin) and e_z to
// (-sin, 0, cos): a positive angle turns the spine towards +z.
glm::dvec3 turned(const glm::dvec3& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x - s * v.z, v.y, s * v.x + c * v.z};
}

const double kPi = 3.14159265358979323846;
// Angles up to the limit pi, both signs; widths: a step (0) and two ramps.
const double kHingeAngles[] = {0.3, -0.7, 1.2, -2.0, kPi, -kPi};
const double kHingeWidths[] = {0.0, 0.05, 0.3};

// A vertex off the spine with a normal and a tangent that are not axis-aligned.
LocalVertex off_spine(double x) {
  return {{x, 0.04, -0.03},
          glm::normalize(glm::dvec3(0.3, -0.2, 0.9)),
          glm::normalize(glm::dvec3(0.9, 0.1, -0.3))};
}

TEST(HingeReference, LeavesEverythingBehindItsBaseUntouched) {
  for (double angle : kHingeAngles) {
    for (double width : kHingeWidths) {
      for (NormalMode normals : kNormalModes) {
        for (double x : {-0.5, -0.1, -1e-9, 0.0}) {
          const LocalVertex rest = off_spine(x);
          const LocalVertex bent = hinge_local_vertex(rest, angle, width, normals);
          EXPECT_LT(glm::length(bent.position - rest.position), 1e-15) << angle << " " << x;
          EXPECT_LT(glm::length(bent.normal - rest.normal), 1e-15) << angle << " " << x;
          EXPECT_LT(glm::length(bent.tangent - rest.tangent), 1e-15) << angle << " " << x;
        }
      }
    }
  }
}

TEST(HingeReference, TurnsRigidlyByItsAnglePastTheRamp) {
  // Past the ramp (x >= width) the part turns as one body: p' = f(width) +
  // R (p - (width, 0, 0)), normals and tangents by R, in both normal modes (no
  // curvature there, so the Jacobian is R itself). f(width) is the end of the circular
  // ramp of radius width / angle: (r sin(angle), 0, r (1 - cos(angle))).
  for (double angle : kHingeAngles) {
    for (double width : kHingeWidths) {
      const glm::dvec3 ramp_end = width == 0.0
                                      ? glm::dvec3(0.0)
                                      : glm::dvec3(width / angle * std::sin(angle), 0.0,
                                                   width / angle * (1.0 - std::cos(angle)));
      for (NormalMode normals : kNormalModes) {
        for (double x : {width, width + 1e-9, width + 0.1, 0.5, 1.0}) {
          if (x == 0.0) continue;  // the step's base belongs to the untouched side
          const LocalVertex rest = off_spine(x);
          const LocalVertex bent = hinge_local_vertex(rest, angle, width, normals);
          SCOPED_TRACE(testing::Message() << "angle " << angle << " width " << width << " x " << x);
          EXPECT_LT(
              glm::length(bent.position -
                          (ramp_end + turned(rest.position - glm::dvec3(width, 0, 0), angle))),
              1e-14);
          EXPECT_LT(glm::length(bent.normal - turned(rest.normal, angle)), 1e-14);
          EXPECT_LT(glm::length(bent.tangent - turned(rest.tangent, angle)), 1e-14);
        }
      }
    }
  }
}

TEST(HingeReference, RampIsACircularArcThatKeepsTheSpineLength) {
  // Through the ramp the spine bends into an arc of radius width / |angle| about
  // (0, 0, width / angle), its normal pointing at the centre's side; sampled from
  // behind the base to past the ramp, the spine keeps its length.
  const int samples = 20001;
  for (double angle : kHingeAngles) {
    for (double width : {0.05, 0.3}) {
      const double r = width / angle;
      const double start = -0.2, end = width + 0.3;
      double length = 0.0;
      glm::dvec3 previous{};
      for (int i = 0; i < samples; ++i) {
        const double x = start + (end - start) * i / (samples - 1);
        const LocalVertex bent = hinge_local_vertex({{x, 0.0, 0.0}, {0.0, 0.0, 1.0}, {1, 0, 0}},
                                                    angle, width, NormalMode::kRotate);
        if (i > 0) length += glm::length(bent.position - previous);
        previous = bent.position;
        if (x > 0.0 && x < width) {
          SCOPED_TRACE(testing::Message() << "angle " << angle << " width " << width << " x " << x);
          EXPECT_NEAR(glm::length(bent.position - glm::dvec3(0.0, 0.0, r)), std::fabs(r), 1e-12);
          // The spine's direction turns by angle x / width: tangent (cos, 0, sin).
          EXPECT_LT(glm::length(bent.tangent - turned({1.0, 0.0, 0.0}, angle * x / width)), 1e-12);
          EXPECT_LT(glm::length(bent.normal - turned({0.0, 0.0, 1.0}, angle * x / width)), 1e-12);
        }
      }
      EXPECT_NEAR(length, end - start, 1e-7 * (end - start)) << angle << " " << width;
    }
  }
}

TEST(HingeReference, PositiveAngleTurnsTowardsPlusZ) {
  for (double width : kHingeWidths) {
    for (double angle : {0.4, kPi / 2, 2.5}) {  // sin(angle) > 0: past the ramp, z grows
      const LocalVertex tip{{1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}};
      const LocalVertex up = hinge_local_vertex(tip, angle, width, NormalMode::kRotate);
      const LocalVertex down = hinge_local_vertex(tip, -angle, width, NormalMode::kRotate);
      EXPECT_GT(up.position.z, 0.1) << angle << " " << width;
      EXPECT_LT(down.position.z, -0.1) << angle << " " << width;
      EXPECT_GT(up.tangent.z, 0.0) << angle << " " << width;
      EXPECT_LT(up.normal.x, 0.0) << angle << " " << width;  // n = (-sin, 0, cos)
      // Opposite angles mirror each other in z.
      const glm::dvec3 flip(1.0, 1.0, -1.0);
      EXPECT_LT(glm::length(up.position * flip - down.position), 1e-14);
    }
  }
  // A quarter turn with a step: the part past the base points along +z.
  const LocalVertex quarter = hinge_local_vertex({{0.5, 0.0, 0.0}, {0.0, 0.0, 1.0}, {1, 0, 0}},
                                                 kPi / 2, 0.0, NormalMode::kRotate);
  EXPECT_LT(glm::length(quarter.position - glm::dvec3(0.0, 0.0, 0.5)), 1e-15);
  EXPECT_LT(glm::length(quarter.tangent - glm::dvec3(0.0, 0.0, 1.0)), 1e-15);
  EXPECT_LT(glm::length(quarter.normal - glm::dvec3(-1.0, 0.0, 0.0)), 1e-15);
}

TEST(HingeReference, JacobianNormalsInTheRampScaleTheAlongSpineComponent) {
  // METHOD.md section 6 with k = angle / width in the ramp: normals by
  // R diag(1 / (1 - z k), 1, 1), R the turn by theta = angle x / width.
  const double angle = 1.1, width = 0.3, x = 0.12, z = 0.05;
  const glm::dvec3 rest_normal = glm::normalize(glm::dvec3(0.5, 0.2, 0.8));
  const LocalVertex bent =
      hinge_local_vertex({{x, 0.0, z}, rest_normal, {}}, angle, width, NormalMode::kJacobian);
  const double k = angle / width;
  const glm::dvec3 scaled(rest_normal.x / (1.0 - z * k), rest_normal.y, rest_normal.z);
  const glm::dvec3 expected = glm::normalize(turned(scaled, angle * x / width));
  EXPECT_LT(glm::length(bent.normal - expected), 1e-14);
  // Rotate mode: the plain turn.
  const LocalVertex rotated =
      hinge_local_vertex({{x, 0.0, z}, rest_normal, {}}, angle, width, NormalMode::kRotate);
  EXPECT_LT(glm::length(rotated.normal - turned(rest_normal, angle * x / width)), 1e-14);
}

}  // namespace
}  // namespace finflex
