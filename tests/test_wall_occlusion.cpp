// Occlusion by tank walls (finflex/wall_occlusion.hpp) against rays cast here: every
// sphere the test calls hidden has every sight line to points on it blocked by a face
// of the prism (the faces intersected exactly, as a renderer draws them), and spheres
// that a sight line clearly reaches are not called hidden; bad walls are named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "finflex/error.hpp"
#include "finflex/wall_occlusion.hpp"

namespace finflex {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Whether the sight line from `eye` to `point` leaves the wall's prism through a face
// between its floor and rim before reaching the point: the faces' edges at angles
// 2 pi k / sides on the circle (x = r cos, z = r sin, as the renderer's tank mesh), a
// true cylinder for sides 0.
bool blocked(const glm::dvec3& eye, const glm::dvec3& point, const WallOccluder& wall) {
  const glm::dvec2 e(eye.x - wall.base.x, eye.z - wall.base.z);
  const glm::dvec2 q(point.x - wall.base.x, point.z - wall.base.z);
  const glm::dvec2 d = q - e;
  double exit = -1.0;  // the line's parameter where it leaves the prism, in (0, 1)
  if (wall.sides == 0) {
    // |e + t d| = r: the larger root.
    const double a = glm::dot(d, d), b = 2.0 * glm::dot(e, d),
                 c = glm::dot(e, e) - wall.radius * wall.radius;
    const double disc = b * b - 4.0 * a * c;
    if (disc > 0.0) exit = (-b + std::sqrt(disc)) / (2.0 * a);
  } else {
    for (int k = 0; k < wall.sides; ++k) {
      const double a0 = 2.0 * kPi * k / wall.sides, a1 = 2.0 * kPi * (k + 1) / wall.sides;
      const glm::dvec2 p0 = wall.radius * glm::dvec2(std::cos(a0), std::sin(a0));
      const glm::dvec2 p1 = wall.radius * glm::dvec2(std::cos(a1), std::sin(a1));
      const glm::dvec2 edge = p1 - p0;
      const glm::dvec2 outward(edge.y, -edge.x);  // the polygon is counter-clockwise
      if (glm::dot(d, outward) <= 0.0) continue;  // entering through this side
      const double cross = d.x * edge.y - d.y * edge.x;
      const glm::dvec2 w = p0 - e;
      const double t = (w.x * edge.y - w.y * edge.x) / cross;
      const double s = (w.x * d.y - w.y * d.x) / cross;
      if (s >= 0.0 && s <= 1.0) exit = t;
    }
  }
  if (!(exit > 0.0 && exit < 1.0)) return false;
  const double height = (eye.y - wall.base.y) + exit * (point.y - eye.y);
  return height >= 0.0 && height <= wall.height;
}

// Points on the sphere: its six extremes and `count` uniform on its surface.
std::vector<glm::dvec3> sphere_points(const glm::dvec3& centre, double radius, std::mt19937& random,
                                      int count) {
  std::vector<glm::dvec3> out;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      glm::dvec3 offset(0.0);
      offset[axis] = sign * radius;
      out.push_back(centre + offset);
    }
  }
  std::normal_distribution<double> normal;
  for (int k = 0; k < count; ++k) {
    const glm::dvec3 g(normal(random), normal(random), normal(random));
    out.push_back(centre + radius * glm::normalize(g));
  }
  return out;
}

TEST(WallOcclusion, EverySightLineToAHiddenSphereMeetsAFace) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const WallOccluder walls[] = {{{0.0, 0.0, 0.0}, 1.83, 1.34, 96},
                                {{0.4, -0.2, 1.0}, 1.0, 0.8, 8},
                                {{-2.0, 0.0, 3.0}, 2.5, 1.5, 0}};
  std::size_t hidden = 0, tried = 0;
  for (const WallOccluder& wall : walls) {
    for (int k = 0; k < 20000; ++k) {
      // Eyes outside and inside the wall, above and below its rim; spheres beyond it.
      const double eye_angle = 2.0 * kPi * unit(random);
      const double eye_distance = wall.radius * (0.2 + 4.0 * unit(random));
      const glm::dvec3 eye = wall.base + glm::dvec3(eye_distance * std::cos(eye_angle),
                                                    wall.height * (0.3 + 3.0 * unit(random)),
                                                    eye_distance * std::sin(eye_angle));
      const double sphere_angle = eye_angle + kPi + 1.2 * (unit(random) - 0.5);
      const double sphere_distance = wall.radius * (1.0 + 2.0 * unit(random));
      const glm::dvec3 centre = wall.base + glm::dvec3(sphere_distance * std::cos(sphere_angle),
                                                       wall.height * (0.1 + 0.9 * unit(random)),
                                                       sphere_distance * std::sin(sphere_angle));
      const double radius = wall.radius * 0.15 * unit(random) + 1e-3;
      ++tried;
      if (!wall_hides_sphere(eye, centre, radius, wall)) continue;
      ++hidden;
      for (const glm::dvec3& point : sphere_points(centre, radius, random, 64)) {
        ASSERT_TRUE(blocked(eye, point, wall))
            << "wall " << wall.radius << " x " << wall.height << ", eye (" << eye.x << ", " << eye.y
            << ", " << eye.z << "), sphere (" << centre.x << ", " << centre.y << ", " << centre.z
            << ") r " << radius;
      }
    }
  }
  std::printf("%zu of %zu spheres hidden, every sight line to them blocked\n", hidden, tried);
  EXPECT_GT(hidden, tried / 10);  // the scenes exercise the test
}

TEST(WallOcclusion, ASphereThatASightLineReachesIsNotHidden) {
  const WallOccluder wall{{0.0, 0.0, 0.0}, 1.83, 1.34, 96};
  // Behind the wall, seen level and low: hidden; the same sphere above the rim, or the
  // eye high above the tank, or the sphere inside the wall: not.
  const glm::dvec3 eye{0.0, 0.6, 8.0};
  EXPECT_TRUE(wall_hides_sphere(eye, {0.0, 0.6, -3.0}, 0.1, wall));
  EXPECT_FALSE(wall_hides_sphere(eye, {0.0, 2.0, -3.0}, 0.1, wall));
  EXPECT_FALSE(wall_hides_sphere({0.0, 30.0, 0.5}, {0.0, 0.6, -3.0}, 0.1, wall));
  EXPECT_FALSE(wall_hides_sphere(eye, {0.0, 0.6, -1.0}, 0.1, wall));
  // Beside the wall: a sight line passes it.
  EXPECT_FALSE(wall_hides_sphere(eye, {4.0, 0.6, -3.0}, 0.1, wall));
  // The sphere across the wall's rim line: partly seen.
  EXPECT_FALSE(wall_hides_sphere(eye, {0.0, 1.40, -3.0}, 0.3, wall));
  // An eye inside the tank: what is beyond the far wall is hidden, what is inside not.
  EXPECT_TRUE(wall_hides_sphere({0.0, 0.5, 0.5}, {0.0, 0.5, -4.0}, 0.2, wall));
  EXPECT_FALSE(wall_hides_sphere({0.0, 0.5, 0.5}, {0.0, 0.5, -1.0}, 0.2, wall));
  // The eye inside the sphere's horizontal disc: never.
  EXPECT_FALSE(wall_hides_sphere({0.0, 10.0, -3.0}, {0.0, 0.6, -3.0}, 0.5, wall));
}

TEST(WallOcclusion, BadWallsAreNamed) {
  const auto field = [](const WallOccluder& wall) {
    try {
      wall.validate("occluders[2]");
    } catch (const Error& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(field({{0.0, 0.0, 0.0}, 1.0, 1.0, 96}), "accepted");
  EXPECT_EQ(field({{0.0, 0.0, 0.0}, 1.0, 1.0, 0}), "accepted");
  EXPECT_EQ(field({{NAN, 0.0, 0.0}, 1.0, 1.0, 96}), "occluders[2].base");
  EXPECT_EQ(field({{0.0, 0.0, 0.0}, 0.0, 1.0, 96}), "occluders[2].radius");
  EXPECT_EQ(field({{0.0, 0.0, 0.0}, 1.0, -1.0, 96}), "occluders[2].height");
  EXPECT_EQ(field({{0.0, 0.0, 0.0}, 1.0, INFINITY, 96}), "occluders[2].height");
  EXPECT_EQ(field({{0.0, 0.0, 0.0}, 1.0, 1.0, 2}), "occluders[2].sides");
  EXPECT_EQ(field({{0.0, 0.0, 0.0}, 1.0, 1.0, -4}), "occluders[2].sides");
}

}  // namespace
}  // namespace finflex
