// The toolkit's one panorama mapping (equirect.h, Blender's convention): orientation of
// rows and columns, the direction <-> uv round trip, and exact texel solid angles.
#include "phyir/render/equirect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "phyir/core/safe_math.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"

namespace phyir::render {
namespace {

void expect_vec_near(const glm::vec3& a, const glm::vec3& b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Equirect, DirectionToUvToDirectionRoundTrip) {
  Rng rng(7, 1);
  float worst = 0.0f;
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 d = sample_uniform_sphere(rng.next_2d());
    const glm::vec2 uv = equirect_uv(d);
    ASSERT_GE(uv.x, 0.0f);
    ASSERT_LT(uv.x, 1.0f);
    ASSERT_GE(uv.y, 0.0f);
    ASSERT_LE(uv.y, 1.0f);
    worst = std::max(worst, glm::length(equirect_direction(uv) - d));
  }
  // Float acos near |y| = 1 limits theta to a few 1e-4 rad at the very poles; uniform
  // samples rarely get there.
  std::cout << "worst direction round-trip error " << worst << "\n";
  EXPECT_LT(worst, 2e-5f) << "worst round-trip error " << worst;
}

TEST(Equirect, UvToDirectionToUvRoundTrip) {
  for (int j = 1; j < 64; ++j) {
    for (int i = 0; i < 128; ++i) {
      const glm::vec2 uv((i + 0.5f) / 128.0f, j / 64.0f);
      const glm::vec2 back = equirect_uv(equirect_direction(uv));
      EXPECT_NEAR(back.x, uv.x, 2e-6f) << "i " << i << " j " << j;
      EXPECT_NEAR(back.y, uv.y, 2e-5f) << "i " << i << " j " << j;
    }
  }
}

TEST(Equirect, RowZeroLooksUp) {
  // v = 0 is exactly +Y for every u.
  for (float u : {0.0f, 0.25f, 0.5f, 0.9f}) expect_vec_near(equirect_direction({u, 0.0f}), {0, 1, 0}, 1e-6f);
  // Every pixel centre of row 0 of a 64x32 image is within half a row (pi/64) of +Y.
  const float half_row = kPi / 64.0f;
  for (int i = 0; i < 64; ++i) {
    const glm::vec3 d = equirect_direction({(i + 0.5f) / 64.0f, 0.5f / 32.0f});
    EXPECT_NEAR(d.y, std::cos(half_row), 1e-6f);
  }
  // And the last row looks down.
  expect_vec_near(equirect_direction({0.3f, 1.0f}), {0, -1, 0}, 1e-6f);
}

TEST(Equirect, CentreLooksAlongMinusZ) {
  expect_vec_near(equirect_direction({0.5f, 0.5f}), {0, 0, -1}, 1e-6f);
  const glm::vec2 uv = equirect_uv({0, 0, -1});
  EXPECT_NEAR(uv.x, 0.5f, 1e-7f);
  EXPECT_NEAR(uv.y, 0.5f, 1e-7f);
  // The centre pixel of an even-sized image straddles -Z.
  const glm::vec3 centre = equirect_direction({(32 + 0.5f) / 64.0f, (16 + 0.5f) / 32.0f});
  EXPECT_LT(centre.z, -0.99f);
}

TEST(Equirect, UGrowsTowardsPlusX) {
  expect_vec_near(equirect_direction({0.75f, 0.5f}), {1, 0, 0}, 1e-6f);
  expect_vec_near(equirect_direction({0.25f, 0.5f}), {-1, 0, 0}, 1e-6f);
  expect_vec_near(equirect_direction({0.0f, 0.5f}), {0, 0, 1}, 1e-6f);
  EXPECT_NEAR(equirect_uv({1, 0, 0}).x, 0.75f, 1e-7f);
  EXPECT_NEAR(equirect_uv({-1, 0, 0}).x, 0.25f, 1e-7f);
  // Just right of the centre column has x > 0.
  EXPECT_GT(equirect_direction({0.51f, 0.5f}).x, 0.0f);
  EXPECT_LT(equirect_direction({0.49f, 0.5f}).x, 0.0f);
}

TEST(Equirect, TexelSolidAnglesSumToFourPi) {
  const int sizes[][2] = {{1, 1}, {1, 8}, {8, 1}, {7, 3}, {64, 32}, {512, 256}, {2048, 1024}};
  for (const auto& s : sizes) {
    double sum = 0.0;
    for (int j = 0; j < s[1]; ++j) sum += double(equirect_texel_solid_angle(j, s[0], s[1])) * s[0];
    EXPECT_NEAR(sum, 4.0 * M_PI, 4.0 * M_PI * 1e-6) << s[0] << "x" << s[1];
  }
  // The polar rows are the smallest, the equator rows the largest, symmetric about it.
  EXPECT_NEAR(equirect_texel_solid_angle(0, 64, 32) / equirect_texel_solid_angle(31, 64, 32), 1.0f, 1e-5f);
  EXPECT_LT(equirect_texel_solid_angle(0, 64, 32), equirect_texel_solid_angle(15, 64, 32));
}

TEST(Equirect, UvDensityMatchesTexelSolidAngle) {
  // A texel covers 1/(W H) of uv space; its solid angle is that divided by the uv->sphere
  // density at its centre, up to the curvature of sin(theta) over the row (~1e-4 here).
  const int w = 512, h = 256;
  for (int j = 1; j < h - 1; j += 17) {
    const float theta = kPi * (j + 0.5f) / h;
    const float predicted = 1.0f / (float(w) * h * equirect_uv_pdf_to_solid_angle(std::sin(theta)));
    EXPECT_NEAR(predicted / equirect_texel_solid_angle(j, w, h), 1.0f, 1e-3f) << "row " << j;
  }
  EXPECT_EQ(equirect_uv_pdf_to_solid_angle(0.0f), 0.0f);
}

}  // namespace
}  // namespace phyir::render
