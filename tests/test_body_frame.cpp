// BodyFrame conversions and validation, and find_body_frame on the bundled fish:
// expected head/dorsal directions, unit local length, equivariance under rigid
// motions, overrides, degenerate inputs.
#include "finflex/body_frame.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "finflex/error.hpp"
#include "finflex/mesh.hpp"
#include "finflex/mesh_io.hpp"
#include "support/synthetic_fish.hpp"
#include "support/test_support.hpp"

namespace finflex {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A bundled fish; glTF node transforms are applied (the Barramundi turns 180 deg about Y).
Mesh load_fish(const std::string& relative) { return load_mesh(test::data_path(relative)); }

// ---------------------------------------------------------------------------------
// Helpers.

// Runs `call`, expects finflex::Error with `code` and `field`, returns its message.
std::string expect_error(const std::function<void()>& call, ErrorCode code,
                         const std::string& field) {
  try {
    call();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no finflex::Error thrown (expected field " << field << ")";
  return "";
}

void expect_near(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance,
                 const std::string& what) {
  EXPECT_LE(glm::length(actual - expected), tolerance)
      << what << ": (" << actual.x << ", " << actual.y << ", " << actual.z << ") vs (" << expected.x
      << ", " << expected.y << ", " << expected.z << ")";
}

// Uniform in [0, 1) from one raw mt19937 draw (portable, unlike the distributions).
double uniform01(std::mt19937& rng) { return static_cast<double>(rng()) / 4294967296.0; }

// Uniform random rotation from three draws (Shoemake).
glm::dmat3 random_rotation(std::mt19937& rng) {
  const double pi = std::acos(-1.0);
  const double u1 = uniform01(rng), u2 = uniform01(rng), u3 = uniform01(rng);
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const glm::dquat q(a * std::cos(2 * pi * u2), a * std::sin(2 * pi * u2),
                     b * std::sin(2 * pi * u3), b * std::cos(2 * pi * u3));
  return glm::mat3_cast(glm::normalize(q));
}

// The 24 rotations that permute the coordinate axes with signs (det +1): exact in float.
std::vector<glm::dmat3> axis_permutation_rotations() {
  std::vector<glm::dmat3> result;
  const std::array<std::array<int, 3>, 6> perms = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (const auto& perm : perms) {
    for (int signs = 0; signs < 8; ++signs) {
      glm::dmat3 m(0.0);
      for (int c = 0; c < 3; ++c)
        m[c][perm[static_cast<std::size_t>(c)]] = (signs >> c & 1) ? -1.0 : 1.0;
      if (glm::determinant(m) > 0.0) result.push_back(m);
    }
  }
  return result;
}

Mesh transformed(const Mesh& mesh, const glm::dmat3& rotation, const glm::dvec3& translation) {
  Mesh out = mesh;
  for (glm::vec3& p : out.positions) p = glm::vec3(rotation * glm::dvec3(p) + translation);
  return out;
}

// Snaps positions to multiples of 2^-16 so that axis permutations plus translations
// by multiples of 2^-16 (|result| < 256) are exact in float.
Mesh snapped_to_grid(const Mesh& mesh) {
  Mesh out = mesh;
  for (glm::vec3& p : out.positions) p = glm::round(p * 65536.0f) / 65536.0f;
  return out;
}

// Local x extent of the vertices: 1 for a frame whose length is the fish's length.
double local_x_extent(const Mesh& mesh, const BodyFrame& frame) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const glm::vec3& p : mesh.positions) {
    const double x = frame.point_to_local(glm::dvec3(p)).x;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return hi - lo;
}

// Expects `moved` == the frame of the mesh moved by p -> R p + t, given `base`:
// axes within `axis_tolerance`, origin and length within `position_tolerance`.
void expect_frame_moved(const BodyFrame& base, const BodyFrame& moved, const glm::dmat3& rotation,
                        const glm::dvec3& translation, double axis_tolerance,
                        double position_tolerance, const std::string& what) {
  expect_near(moved.axis_x, rotation * base.axis_x, axis_tolerance, what + " axis_x");
  expect_near(moved.axis_y, rotation * base.axis_y, axis_tolerance, what + " axis_y");
  expect_near(moved.axis_z, rotation * base.axis_z, axis_tolerance, what + " axis_z");
  expect_near(moved.origin, rotation * base.origin + translation, position_tolerance,
              what + " origin");
  EXPECT_NEAR(moved.length, base.length, position_tolerance) << what << " length";
}

// The largest |coordinate| of the mesh.
double max_abs_coordinate(const Mesh& mesh) {
  double result = 0.0;
  for (const glm::vec3& p : mesh.positions) {
    result =
        std::max({result, std::abs(double{p.x}), std::abs(double{p.y}), std::abs(double{p.z})});
  }
  return result;
}

BodyFrame rotated_frame() {  // an arbitrary valid frame
  BodyFrame frame;
  const glm::dmat3 r = glm::mat3_cast(glm::normalize(glm::dquat(0.8, -0.3, 0.4, 0.2)));
  frame.axis_x = r[0];
  frame.axis_y = r[1];
  frame.axis_z = r[2];
  frame.origin = {1.5, -2.0, 0.25};
  frame.length = 2.75;
  return frame;
}

// A regular icosahedron (edge 2): all its second moments are equal.
Mesh icosahedron() {
  const float phi = static_cast<float>((1.0 + std::sqrt(5.0)) / 2.0);
  Mesh mesh;
  for (float s : {-1.0f, 1.0f}) {
    for (float t : {-phi, phi}) {
      mesh.positions.emplace_back(0.0f, s, t);
      mesh.positions.emplace_back(s, t, 0.0f);
      mesh.positions.emplace_back(t, 0.0f, s);
    }
  }
  const auto edge = [&mesh](std::uint32_t i, std::uint32_t j) {
    return std::abs(glm::distance(mesh.positions[i], mesh.positions[j]) - 2.0f) < 1e-4f;
  };
  for (std::uint32_t i = 0; i < 12; ++i) {
    for (std::uint32_t j = i + 1; j < 12; ++j) {
      for (std::uint32_t k = j + 1; k < 12; ++k) {
        if (edge(i, j) && edge(j, k) && edge(i, k))
          mesh.indices.insert(mesh.indices.end(), {i, j, k});
      }
    }
  }
  return mesh;
}

// A closed prism along x (length 2) over a regular 12-gon (radius 0.3): its
// cross-section's second moments are equal in every direction.
Mesh round_prism() {
  const double pi = std::acos(-1.0);
  const std::uint32_t n = 12;
  Mesh mesh;
  for (float x : {-1.0f, 1.0f}) {
    for (std::uint32_t k = 0; k < n; ++k) {
      const double a = 2.0 * pi * k / n;
      mesh.positions.emplace_back(x, static_cast<float>(0.3 * std::cos(a)),
                                  static_cast<float>(0.3 * std::sin(a)));
    }
  }
  mesh.positions.emplace_back(-1.0f, 0.0f, 0.0f);
  mesh.positions.emplace_back(1.0f, 0.0f, 0.0f);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t k1 = (k + 1) % n;
    mesh.indices.insert(mesh.indices.end(), {k, k1, n + k1, k, n + k1, n + k});
    mesh.indices.insert(mesh.indices.end(), {2 * n, k1, k, 2 * n + 1, n + k, n + k1});
  }
  return mesh;
}

// ---------------------------------------------------------------------------------
// BodyFrame.

TEST(BodyFrame, IdentityLeavesPointsAndVectorsUnchanged) {
  const BodyFrame frame = BodyFrame::identity();
  EXPECT_NO_THROW(frame.validate());
  const glm::dvec3 p(0.3, -1.25, 7.5);
  EXPECT_EQ(frame.point_to_local(p), p);
  EXPECT_EQ(frame.point_to_mesh(p), p);
  EXPECT_EQ(frame.vector_to_local(p), p);
  EXPECT_EQ(frame.vector_to_mesh(p), p);
}

TEST(BodyFrame, PointToLocalIsRotationThenScaleAboutOrigin) {
  BodyFrame frame;  // spine along mesh +z, dorsal along +y, lateral = z x y = -x
  frame.axis_x = {0, 0, 1};
  frame.axis_y = {0, 1, 0};
  frame.axis_z = {-1, 0, 0};
  frame.origin = {1, 2, 3};
  frame.length = 2;
  ASSERT_NO_THROW(frame.validate());
  expect_near(frame.point_to_local({1, 2, 5}), {1, 0, 0}, 1e-15, "head point");
  expect_near(frame.point_to_local({1, 3, 3}), {0, 0.5, 0}, 1e-15, "dorsal point");
  expect_near(frame.point_to_local({0, 2, 3}), {0, 0, 0.5}, 1e-15, "lateral point");
  expect_near(frame.vector_to_local({0, 0, 4}), {4, 0, 0}, 1e-15, "vector: rotation only");
}

TEST(BodyFrame, ToLocalAndBackRoundTrips) {
  const BodyFrame frame = rotated_frame();
  ASSERT_NO_THROW(frame.validate());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  for (int i = 0; i < 100; ++i) {
    const glm::dvec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
    expect_near(frame.point_to_mesh(frame.point_to_local(p)), p, 1e-13, "point mesh->local->mesh");
    expect_near(frame.point_to_local(frame.point_to_mesh(p)), p, 1e-13, "point local->mesh->local");
    expect_near(frame.vector_to_mesh(frame.vector_to_local(p)), p, 1e-13, "vector round trip");
    // Distances scale by 1/length; directions keep their length.
    EXPECT_NEAR(glm::length(frame.point_to_local(p) - frame.point_to_local(frame.origin)),
                glm::length(p - frame.origin) / frame.length, 1e-13);
    EXPECT_NEAR(glm::length(frame.vector_to_local(p)), glm::length(p), 1e-13);
  }
}

TEST(BodyFrame, ValidateNamesTheBadField) {
  BodyFrame frame = BodyFrame::identity();
  frame.axis_x = {2, 0, 0};
  std::string message =
      expect_error([&] { frame.validate(); }, ErrorCode::kInvalidArgument, "axis_x");
  EXPECT_NE(message.find("axis_x = (2, 0, 0)"), std::string::npos) << message;
  EXPECT_NE(message.find("not unit"), std::string::npos) << message;

  frame = BodyFrame::identity();
  frame.axis_y = glm::normalize(glm::dvec3(1, 1, 0));
  message = expect_error([&] { frame.validate(); }, ErrorCode::kInvalidArgument, "axis_y");
  EXPECT_NE(message.find("not orthogonal to axis_x"), std::string::npos) << message;

  frame = BodyFrame::identity();
  frame.axis_z = {0, 0, -1};
  message = expect_error([&] { frame.validate(); }, ErrorCode::kInvalidArgument, "axis_z");
  EXPECT_NE(message.find("left-handed"), std::string::npos) << message;
  EXPECT_NE(message.find("(0, 0, -1)"), std::string::npos) << message;

  frame = BodyFrame::identity();
  frame.axis_z = {0, kNaN, 1};
  expect_error([&] { frame.validate(); }, ErrorCode::kInvalidArgument, "axis_z");

  frame = BodyFrame::identity();
  frame.length = 0.0;
  message = expect_error([&] { frame.validate(); }, ErrorCode::kInvalidArgument, "length");
  EXPECT_NE(message.find("length = 0"), std::string::npos) << message;
  frame.length = -1.0;
  expect_error([&] { frame.validate(); }, ErrorCode::kInvalidArgument, "length");
  frame.length = std::numeric_limits<double>::infinity();
  expect_error([&] { frame.validate(); }, ErrorCode::kInvalidArgument, "length");

  frame = BodyFrame::identity();
  frame.origin = {0, kNaN, 0};
  message = expect_error([&] { frame.validate(); }, ErrorCode::kInvalidArgument, "origin");
  EXPECT_NE(message.find("origin = "), std::string::npos) << message;
  EXPECT_NE(message.find("nan"), std::string::npos) << message;

  frame = rotated_frame();  // within tolerance after a float round trip of the axes
  frame.axis_x = glm::dvec3(glm::vec3(frame.axis_x));
  EXPECT_NO_THROW(frame.validate());
}

// ---------------------------------------------------------------------------------
// find_body_frame on the bundled fish.

struct FishCase {
  const char* path;
  glm::dvec3 head;    // towards the head, in mesh coordinates (by inspection)
  glm::dvec3 dorsal;  // towards the back
};

// By inspection of renders, the eyes and the fins (see the header comment):
//  - Blub (both resolutions): snout at +z, caudal fin at -z, dorsal fin at +y. The
//    full-resolution Blub's tail is bent towards +x, which tilts its spine by ~10 deg.
//  - Barramundi (with the node's 180 deg turn about Y): snout at +z, forked caudal fin
//    at -z, dorsal fins at +y (the raw accessors have the head at -z).
const FishCase kFishCases[] = {
    {"blub/fish.obj", {0, 0, 1}, {0, 1, 0}},
    {"blub/fish_low_resolution.obj", {0, 0, 1}, {0, 1, 0}},
    {"barramundi/BarramundiFish.gltf", {0, 0, 1}, {0, 1, 0}},
};

void PrintTo(const FishCase& fish, std::ostream* out) { *out << fish.path; }

class BundledFishFrame : public testing::TestWithParam<FishCase> {};

TEST_P(BundledFishFrame, FindsHeadDorsalLengthAndPivot) {
  const FishCase& fish = GetParam();
  const Mesh mesh = load_fish(fish.path);
  const BodyFrame frame = find_body_frame(mesh);
  ASSERT_NO_THROW(frame.validate());
  const double cos15 = std::cos(15.0 * std::acos(-1.0) / 180.0);
  EXPECT_GT(glm::dot(frame.axis_x, fish.head), cos15) << "head";
  EXPECT_GT(glm::dot(frame.axis_y, fish.dorsal), cos15) << "dorsal";
  EXPECT_GT(glm::dot(frame.axis_z, glm::cross(fish.head, fish.dorsal)), cos15) << "lateral";
  EXPECT_NEAR(local_x_extent(mesh, frame), 1.0, 1e-12);

  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(frame.origin[c], lo[c]) << "pivot inside the bounding box, axis " << c;
    EXPECT_LT(frame.origin[c], hi[c]) << "pivot inside the bounding box, axis " << c;
  }
  // The length is the fish's, along its spine: close to its extent along `head`.
  EXPECT_NEAR(frame.length, glm::dot(hi - lo, fish.head), 0.1 * frame.length);
}

// Generic rotations + translations; the moved mesh is rounded to float again, so
// the frame moves only up to that rounding (relative ~1e-7) amplified by the axes'
// eigenvalue gaps.
TEST_P(BundledFishFrame, EquivariantUnderRandomRigidMotions) {
  const Mesh mesh = load_fish(GetParam().path);
  const BodyFrame base = find_body_frame(mesh);
  std::mt19937 rng(20240611);
  for (int i = 0; i < 5; ++i) {
    const glm::dmat3 rotation = random_rotation(rng);
    const glm::dvec3 translation =
        20.0 * glm::dvec3(uniform01(rng), uniform01(rng), uniform01(rng)) - glm::dvec3(10.0);
    const Mesh moved_mesh = transformed(mesh, rotation, translation);
    // A few float roundings of the moved coordinates; axes: observed <= 1.5e-6.
    const double position_tolerance =
        8.0 * std::numeric_limits<float>::epsilon() * max_abs_coordinate(moved_mesh);
    expect_frame_moved(base, find_body_frame(moved_mesh), rotation, translation, 2e-5,
                       position_tolerance,
                       std::string(GetParam().path) + " motion " + std::to_string(i));
  }
}

// Axis permutations + translations on a 2^-16 grid move the float mesh exactly, so
// the frame must move to double round-off.
TEST_P(BundledFishFrame, EquivariantToRoundOffUnderExactRigidMotions) {
  const Mesh mesh = snapped_to_grid(load_fish(GetParam().path));
  const BodyFrame base = find_body_frame(mesh);
  const std::vector<glm::dmat3> rotations = axis_permutation_rotations();
  ASSERT_EQ(rotations.size(), 24u);
  std::mt19937 rng(42);
  for (int i = 0; i < 5; ++i) {
    const glm::dmat3& rotation = rotations[rng() % rotations.size()];
    glm::dvec3 translation;
    for (int c = 0; c < 3; ++c) {
      translation[c] =
          static_cast<double>(static_cast<std::int64_t>(rng() % (16u << 16)) - (8 << 16)) / 65536.0;
    }
    const Mesh moved_mesh = transformed(mesh, rotation, translation);
    for (std::size_t v = 0; v < mesh.positions.size(); v += 97) {  // the move is exact
      ASSERT_EQ(glm::dvec3(moved_mesh.positions[v]),
                rotation * glm::dvec3(mesh.positions[v]) + translation);
    }
    expect_frame_moved(base, find_body_frame(moved_mesh), rotation, translation, 1e-9,
                       1e-9 * base.length,
                       std::string(GetParam().path) + " exact motion " + std::to_string(i));
  }
}

INSTANTIATE_TEST_SUITE_P(Fish, BundledFishFrame, testing::ValuesIn(kFishCases),
                         [](const testing::TestParamInfo<FishCase>& param_info) {
                           std::string name = param_info.param.path;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(FindBodyFrame, RecoversTheSyntheticFishFrame) {
  const Mesh mesh = test::synthetic_fish();  // built in its own frame, head at +x
  FrameOptions options;
  options.dorsal_direction = glm::dvec3(0, 1, 0);  // up/down symmetric: sign by option
  const BodyFrame frame = find_body_frame(mesh, options);
  expect_near(frame.axis_x, {1, 0, 0}, 1e-6, "axis_x");
  expect_near(frame.axis_y, {0, 1, 0}, 1e-6, "axis_y");
  expect_near(frame.axis_z, {0, 0, 1}, 1e-6, "axis_z");
  EXPECT_NEAR(frame.length, 1.0, 1e-6);
  EXPECT_NEAR(frame.origin.y, 0.0, 1e-6);
  EXPECT_NEAR(frame.origin.z, 0.0, 1e-6);
}

// ---------------------------------------------------------------------------------
// Overrides.

TEST(FindBodyFrame, OverridesOrientAndPlaceTheFrame) {
  const Mesh mesh = load_fish("blub/fish_low_resolution.obj");
  const BodyFrame automatic = find_body_frame(mesh);

  FrameOptions options;
  options.head_direction = -automatic.axis_x + 0.5 * automatic.axis_y;  // only the sign counts
  BodyFrame frame = find_body_frame(mesh, options);
  expect_near(frame.axis_x, -automatic.axis_x, 1e-12, "head flipped: axis_x");
  expect_near(frame.axis_y, automatic.axis_y, 1e-12, "head flipped: axis_y");
  expect_near(frame.axis_z, -automatic.axis_z, 1e-12, "head flipped: axis_z");
  expect_near(frame.origin, automatic.origin, 1e-12, "head flipped: origin");
  EXPECT_EQ(frame.length, automatic.length);

  options = {};
  options.dorsal_direction = -automatic.axis_y;
  frame = find_body_frame(mesh, options);
  expect_near(frame.axis_x, automatic.axis_x, 1e-12, "dorsal flipped: axis_x");
  expect_near(frame.axis_y, -automatic.axis_y, 1e-12, "dorsal flipped: axis_y");
  expect_near(frame.axis_z, -automatic.axis_z, 1e-12, "dorsal flipped: axis_z");

  // A "dorsal" closer to the lateral axis makes that principal axis dorsal.
  options.dorsal_direction = automatic.axis_z + 0.3 * automatic.axis_y;
  frame = find_body_frame(mesh, options);
  expect_near(frame.axis_x, automatic.axis_x, 1e-12, "dorsal sideways: axis_x");
  expect_near(frame.axis_y, automatic.axis_z, 1e-12, "dorsal sideways: axis_y");
  expect_near(frame.axis_z, -automatic.axis_y, 1e-12, "dorsal sideways: axis_z");

  options = {};
  options.pivot = glm::dvec3(0.1, -0.2, 0.7);
  frame = find_body_frame(mesh, options);
  EXPECT_EQ(frame.origin, *options.pivot);
  expect_near(frame.axis_x, automatic.axis_x, 1e-12, "pivot: axis_x");
  expect_near(frame.axis_y, automatic.axis_y, 1e-12, "pivot: axis_y");
  EXPECT_NEAR(frame.length, automatic.length, 1e-12);
  EXPECT_NEAR(local_x_extent(mesh, frame), 1.0, 1e-12);
}

TEST(FindBodyFrame, RejectsBadOverrides) {
  const Mesh mesh = load_fish("blub/fish_low_resolution.obj");
  const BodyFrame automatic = find_body_frame(mesh);
  FrameOptions options;
  options.head_direction = automatic.axis_y;  // perpendicular to the spine
  std::string message = expect_error([&] { find_body_frame(mesh, options); },
                                     ErrorCode::kInvalidArgument, "options.head_direction");
  EXPECT_NE(message.find("perpendicular"), std::string::npos) << message;
  options.head_direction = glm::dvec3(0.0);
  expect_error([&] { find_body_frame(mesh, options); }, ErrorCode::kInvalidArgument,
               "options.head_direction");
  options.head_direction = glm::dvec3(kNaN, 0, 1);
  expect_error([&] { find_body_frame(mesh, options); }, ErrorCode::kInvalidArgument,
               "options.head_direction");

  options = {};
  options.dorsal_direction = automatic.axis_x;  // along the spine
  expect_error([&] { find_body_frame(mesh, options); }, ErrorCode::kInvalidArgument,
               "options.dorsal_direction");
  options.dorsal_direction = glm::dvec3(0, std::numeric_limits<double>::infinity(), 0);
  expect_error([&] { find_body_frame(mesh, options); }, ErrorCode::kInvalidArgument,
               "options.dorsal_direction");

  options = {};
  options.pivot = glm::dvec3(0, 0, kNaN);
  message = expect_error([&] { find_body_frame(mesh, options); }, ErrorCode::kInvalidArgument,
                         "options.pivot");
  EXPECT_NE(message.find("options.pivot = "), std::string::npos) << message;
}

// ---------------------------------------------------------------------------------
// Degenerate and invalid meshes.

TEST(FindBodyFrame, RejectsZeroArea) {
  Mesh line;
  for (float x : {0.0f, 1.0f, 2.0f, 3.0f}) line.positions.emplace_back(x, 0.5f * x, 0.0f);
  line.indices = {0, 1, 2, 1, 2, 3};
  const std::string message =
      expect_error([&] { find_body_frame(line); }, ErrorCode::kInvalidMesh, "mesh");
  EXPECT_NE(message.find("zero surface area"), std::string::npos) << message;

  Mesh no_triangles;
  no_triangles.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  expect_error([&] { find_body_frame(no_triangles); }, ErrorCode::kInvalidMesh, "mesh");
}

TEST(FindBodyFrame, RejectsAnIcosahedronWithoutASpine) {
  const Mesh mesh = icosahedron();
  ASSERT_EQ(mesh.triangle_count(), 20u);
  const std::string message =
      expect_error([&] { find_body_frame(mesh); }, ErrorCode::kInvalidMesh, "mesh");
  EXPECT_NE(message.find("spine is undefined"), std::string::npos) << message;
}

TEST(FindBodyFrame, RoundCrossSectionNeedsADorsalDirection) {
  const Mesh mesh = round_prism();
  const std::string message =
      expect_error([&] { find_body_frame(mesh); }, ErrorCode::kInvalidMesh, "mesh");
  EXPECT_NE(message.find("dorsal_direction"), std::string::npos) << message;

  FrameOptions options;
  options.dorsal_direction = glm::dvec3(0.2, 1.0, 0.1);  // projected across the spine
  options.head_direction = glm::dvec3(1.0, 0.0, 0.0);    // both ends alike
  const BodyFrame frame = find_body_frame(mesh, options);
  expect_near(frame.axis_x, {1, 0, 0}, 1e-6, "axis_x");
  expect_near(frame.axis_y, glm::normalize(glm::dvec3(0, 1, 0.1)), 1e-6, "axis_y");
  EXPECT_NO_THROW(frame.validate());
  EXPECT_NEAR(frame.length, 2.0, 1e-6);
}

TEST(FindBodyFrame, RejectsInvalidMeshes) {
  expect_error([] { find_body_frame(Mesh{}); }, ErrorCode::kInvalidMesh, "positions");
  Mesh mesh = round_prism();
  mesh.indices[4] = 1000;
  expect_error([&] { find_body_frame(mesh); }, ErrorCode::kInvalidMesh, "indices[4]");
  mesh = round_prism();
  mesh.positions[3].y = std::numeric_limits<float>::quiet_NaN();
  expect_error([&] { find_body_frame(mesh); }, ErrorCode::kInvalidMesh, "positions[3].y");
}

}  // namespace
}  // namespace finflex
