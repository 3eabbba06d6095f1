// SphericalTriangle: its solid angle against Van Oosterom and Strackee's formula and, as the
// code computes it that way too, against Girard's (the sum of the corner angles less pi) and
// an octant's pi / 2, up to a triangle wider than pi (the formula's other branch); and its
// samples inside the triangle and uniform in solid angle (the share falling in a part of it
// is that part's share of the solid angle), for a far small triangle, a near large one and
// a thin strip seen from beside it.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/constants.hpp>

#include "phyir/render/spherical_triangle.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

// Whether unit d points into the triangle (p0, p1, p2) seen from the origin.
bool inside(const glm::dvec3& d, const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2) {
  const double orientation = glm::dot(p0, glm::cross(p1, p2)) > 0.0 ? 1.0 : -1.0;
  const double slack = -1e-9;
  return orientation * glm::dot(d, glm::cross(p0, p1)) >= slack && orientation * glm::dot(d, glm::cross(p1, p2)) >= slack &&
         orientation * glm::dot(d, glm::cross(p2, p0)) >= slack;
}

struct Case {
  const char* name;
  glm::vec3 p0, p1, p2;
};
const Case kCases[] = {
    {"far and small", {3.0f, 1.0f, -2.0f}, {3.1f, 1.0f, -2.0f}, {3.0f, 1.1f, -2.05f}},
    {"near and large", {-1.0f, 0.3f, -0.2f}, {1.0f, 0.3f, -0.2f}, {0.0f, 0.3f, 1.5f}},
    {"thin strip from beside", {0.1f, -0.03f, -0.3f}, {0.1f, -0.03f, 0.3f}, {0.1f, -0.028f, 0.3f}},
};

TEST(SphericalTriangle, SolidAngleIsVanOosteromsAndSamplesAreInsideAndUniform) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    SphericalTriangle triangle;
    ASSERT_TRUE(triangle.set(glm::vec3(0.0f), c.p0, c.p1, c.p2));
    const glm::dvec3 p0(c.p0), p1(c.p1), p2(c.p2);
    const double omega = test::triangle_solid_angle(p0, p1, p2);
    EXPECT_NEAR(triangle.solid_angle(), omega, 1e-6 * omega);
    // A part of it: the triangle (p0, p1, m), m the midpoint of the edge p0-p2.
    const glm::dvec3 m = 0.5 * (p0 + p2);
    const double share = test::triangle_solid_angle(p0, p1, m) / omega;
    constexpr int n = 256;
    int in_part = 0, outside = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const glm::dvec3 d(triangle.sample(glm::vec2((i + 0.5f) / n, (j + 0.5f) / n)));
        EXPECT_NEAR(glm::length(d), 1.0, 1e-5);
        if (!inside(d, p0, p1, p2)) ++outside;
        if (inside(d, p0, p1, m)) ++in_part;
      }
    EXPECT_LE(outside, n * n / 10000) << "a few on the edges, from rounding";
    // A stratified grid resolves the cut to about 1 / n of the triangle.
    EXPECT_NEAR(double(in_part) / (n * n), share, 4.0 / n);
  }
}

// Girard's theorem: the sum of the interior angles less pi, each the angle between the planes
// through the vertex and its two neighbours.
double girard_solid_angle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  auto corner = [](const glm::dvec3& v, const glm::dvec3& p, const glm::dvec3& q) {
    return std::acos(glm::dot(glm::normalize(glm::cross(v, p)), glm::normalize(glm::cross(v, q))));
  };
  return corner(a, b, c) + corner(b, c, a) + corner(c, a, b) - glm::pi<double>();
}

TEST(SphericalTriangle, SolidAngleAgreesWithGirardsTheoremBeyondPi) {
  SphericalTriangle octant;
  ASSERT_TRUE(octant.set(glm::vec3(0.0f), {1, 0, 0}, {0, 1, 0}, {0, 0, 1}));
  EXPECT_NEAR(octant.solid_angle(), 0.5 * glm::pi<double>(), 1e-12);
  // Three points below the equator, 120 degrees apart, round the point's foot: between pi and 2 pi.
  for (const double below : {0.3, 0.05}) {
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::vec3(std::cos(2.0944 * k), std::sin(2.0944 * k), -below);
    SphericalTriangle wide;
    ASSERT_TRUE(wide.set(glm::vec3(0.0f), p[0], p[1], p[2]));
    const double girard = girard_solid_angle(glm::dvec3(p[0]), glm::dvec3(p[1]), glm::dvec3(p[2]));
    EXPECT_GT(girard, glm::pi<double>());
    EXPECT_NEAR(wide.solid_angle(), girard, 1e-9 * girard) << below;
  }
  for (const Case& c : kCases) {
    SphericalTriangle t;
    ASSERT_TRUE(t.set(glm::vec3(0.0f), c.p0, c.p1, c.p2));
    const double girard = girard_solid_angle(glm::dvec3(c.p0), glm::dvec3(c.p1), glm::dvec3(c.p2));
    EXPECT_NEAR(t.solid_angle(), girard, 1e-6 * girard) << c.name;
  }
}

TEST(SphericalTriangle, DegenerateTrianglesHaveNoSolidAngle) {
  SphericalTriangle triangle;
  EXPECT_FALSE(triangle.set(glm::vec3(0.0f), {1, 0, 0}, {1, 1, 0}, {1, 2, 0})) << "collinear";
  EXPECT_FALSE(triangle.set(glm::vec3(0.0f), {1, 0, 0}, {2, 0, 0}, {3, 1, 0})) << "edge-on: its plane holds the point";
  EXPECT_FALSE(triangle.set(glm::vec3(1, 0, 0), {1, 0, 0}, {1, 1, 0}, {1, 0, 1})) << "a vertex at the point";
}

}  // namespace
}  // namespace phyir::render
