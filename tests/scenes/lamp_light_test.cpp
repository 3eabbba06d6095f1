// Lamp lights clear of their lamp's surfaces: a ceiling light's source under its disc moved
// down by its radius, and a source that cannot clear both of two plates.
#include "phyir/scenes/lamp_light.h"

#include <gtest/gtest.h>

#include <cmath>

namespace phyir::scenes {
namespace {

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
