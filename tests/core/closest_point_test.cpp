// closest_point_on_triangle against a dense grid of the triangle's points.
#include "phyir/core/closest_point.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace phyir {
namespace {

TEST(ClosestPoint, OnATriangleIsNoFartherThanAnyOfItsPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec3 a(0.0f), b(1.0f, 0.2f, 0.0f), c(0.3f, 0.9f, 0.4f);
  constexpr int n = 200;
  for (int trial = 0; trial < 200; ++trial) {
    const glm::vec3 p(2.0f * u(rng), 2.0f * u(rng), 2.0f * u(rng));
    const glm::vec3 q = closest_point_on_triangle(p, a, b, c);
    // q lies in the triangle's plane, inside it (barycentrics >= 0 up to round-off).
    const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
    EXPECT_NEAR(glm::dot(q - a, normal), 0.0f, 1e-5f);
    float grid_best = INFINITY;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const glm::vec3 g = a + (b - a) * (float(i) / n) + (c - a) * (float(j) / n);
        grid_best = std::min(grid_best, glm::length(g - p));
      }
    EXPECT_LE(glm::length(q - p), grid_best + 1e-5f);
    EXPECT_GE(glm::length(q - p), grid_best - 0.01f);  // the grid's spacing
  }
}

}  // namespace
}  // namespace phyir
