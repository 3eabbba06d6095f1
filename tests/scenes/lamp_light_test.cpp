// Lamp lights clear of their lamp's surfaces: the nearest point of a triangle against a dense
// grid of its points, and a ceiling light's source under its disc moved down by its radius.
#include "phyir/scenes/lamp_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace phyir::scenes {
namespace {

TEST(LampLight, ClosestPointOnATriangleIsNoFartherThanAnyOfItsPoints) {
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

// A 22 cm square plate at y = 0, as a ceiling light's glowing disc.
AssetMesh plate() {
  AssetMesh m;
  m.positions = {{-0.11f, 0.0f, -0.11f}, {0.11f, 0.0f, -0.11f}, {0.11f, 0.0f, 0.11f}, {-0.11f, 0.0f, 0.11f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST(LampLight, ASourceUnderItsPlateMovesDownByItsRadius) {
  const AssetMesh disc = plate();
  const std::vector<const AssetMesh*> meshes{&disc};
  const glm::vec3 moved = clear_of_surfaces(meshes, glm::vec3(0.01f, -0.004f, 0.02f), 0.0325f);
  EXPECT_NEAR(moved.y, -0.0325f, 1e-5f);
  EXPECT_NEAR(moved.x, 0.01f, 1e-6f);
  EXPECT_NEAR(moved.z, 0.02f, 1e-6f);
  // On the plate: down. Already clear: unchanged.
  EXPECT_NEAR(clear_of_surfaces(meshes, glm::vec3(0.0f), 0.0325f).y, -0.0325f, 1e-5f);
  const glm::vec3 clear(0.0f, -0.1f, 0.0f);
  EXPECT_EQ(clear_of_surfaces(meshes, clear, 0.0325f), clear);
  EXPECT_EQ(clear_of_surfaces({}, clear, 0.0325f), clear);
}

TEST(LampLight, ASourceThatCannotClearEverySurfaceStaysFinite) {
  // Two plates 2 cm apart, a source of radius 3.25 cm between them: no place clears both.
  AssetMesh lower = plate(), upper = plate();
  for (glm::vec3& p : upper.positions) p.y = 0.02f;
  const glm::vec3 moved = clear_of_surfaces({&lower, &upper}, glm::vec3(0.0f, 0.01f, 0.0f), 0.0325f);
  EXPECT_TRUE(std::isfinite(moved.x) && std::isfinite(moved.y) && std::isfinite(moved.z));
  EXPECT_LT(glm::length(moved), 0.2f);
}

}  // namespace
}  // namespace phyir::scenes
