// Probe layout: sizes and their errors, texel directions (inside the texel, uniform in
// solid angle), stratification, and placement (origin = first surface + offset * normal,
// masks for emitters, glass and nothing).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/equirect.h"
#include "phyir/render/probe_grid.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

TEST(ProbeLayout, ParsesSizesAndRejectsBadOnes) {
  int h = 0, w = 0;
  phyir::view::parse_size("128x256", "--probe-grid", &h, &w);
  EXPECT_EQ(h, 128);
  EXPECT_EQ(w, 256);
  EXPECT_THROW(phyir::view::parse_size("128", "--probe-grid", &h, &w), Error);
  EXPECT_THROW(phyir::view::parse_size("16x32x2", "--probe-res", &h, &w), Error);
  EXPECT_THROW(phyir::view::parse_size("axb", "--probe-res", &h, &w), Error);
  ProbeLayout layout;
  EXPECT_NO_THROW(layout.validate());  // the paper's 128x256 grid of 16x32 probes
  EXPECT_EQ(layout.mosaic_height(), 2048);
  EXPECT_EQ(layout.mosaic_width(), 8192);
  layout.res_width = 0;
  try {
    layout.validate();
    FAIL() << "a 16x0 probe was accepted";
  } catch (const SettingError& e) {
    EXPECT_EQ(e.setting(), "probe.res") << e.what();
  }
}

TEST(ProbeTexels, DirectionsStayInsideTheirTexelAndAreUniformInSolidAngle) {
  const int h = 16, w = 32;
  Rng rng(3, 1);
  for (int row : {0, 5, 8, 15}) {
    for (int col : {0, 13, 31}) {
      const double cos0 = std::cos(kPi * row / h), cos1 = std::cos(kPi * (row + 1) / h);
      double mean_cos = 0.0;
      const int n = 20000;
      for (int k = 0; k < n; ++k) {
        const glm::vec3 d = probe_texel_direction(row, col, h, w, rng.next_2d());
        ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
        const glm::vec2 uv = equirect_uv(d);
        ASSERT_GE(uv.x * w, col - 1e-3f);
        ASSERT_LE(uv.x * w, col + 1 + 1e-3f);
        ASSERT_GE(uv.y * h, row - 1e-3f);
        ASSERT_LE(uv.y * h, row + 1 + 1e-3f);
        mean_cos += d.y;
      }
      // Uniform in solid angle <=> cos(theta) uniform between the row's edges.
      EXPECT_NEAR(mean_cos / n, 0.5 * (cos0 + cos1), 0.01 * std::abs(cos0 - cos1)) << row << "," << col;
    }
  }
  // The texel's centre variate (0.5, 0.5) is the middle of cos(theta), not of theta.
  const glm::vec3 c = probe_texel_direction(0, 0, h, w, glm::vec2(0.5f));
  EXPECT_NEAR(c.y, 0.5 * (1.0 + std::cos(kPi / h)), 1e-6);
}

TEST(ProbeTexels, StratifiedSquareUsesEveryCellOnceForSquares) {
  Rng rng(9, 2);
  std::vector<glm::vec2> points;
  stratified_square(16, rng, &points);
  ASSERT_EQ(points.size(), 16u);
  std::vector<int> hits(16, 0);
  for (const glm::vec2& p : points) {
    ASSERT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1);
    ++hits[int(p.y * 4) * 4 + int(p.x * 4)];
  }
  for (int k = 0; k < 16; ++k) EXPECT_EQ(hits[k], 1) << k;
  stratified_square(7, rng, &points);  // 3 x 3 cells, 7 distinct ones
  ASSERT_EQ(points.size(), 7u);
  std::vector<int> cells;
  for (const glm::vec2& p : points) cells.push_back(int(p.y * 3) * 3 + int(p.x * 3));
  std::sort(cells.begin(), cells.end());
  EXPECT_EQ(std::unique(cells.begin(), cells.end()), cells.end());
}

// Over many draws of 24 stratified points (5 x 5 cells), the stratified mean's variance
// across draws against the mean of stratified_mean_variance and of the samples' spread
// (their sample variance over the count).
struct VarianceCheck {
  double across_draws = 0.0, strata_estimate = 0.0, spread_estimate = 0.0;
};
template <typename F>
VarianceCheck check_variance(F&& value_at, int count, int draws) {
  Rng rng(31, 7);
  std::vector<glm::vec2> points;
  std::vector<float> values;
  double sum_mean = 0.0, sum_mean2 = 0.0;
  VarianceCheck check;
  for (int d = 0; d < draws; ++d) {
    stratified_square(count, rng, &points);
    values.clear();
    double sum = 0.0, sum2 = 0.0;
    for (const glm::vec2& p : points) {
      values.push_back(value_at(p, rng));
      sum += values.back(), sum2 += double(values.back()) * values.back();
    }
    const double mean = sum / count;
    sum_mean += mean, sum_mean2 += mean * mean;
    check.strata_estimate += stratified_mean_variance(points, values, 8) / draws;
    check.spread_estimate += (sum2 - sum * sum / count) / (double(count) * (count - 1)) / draws;
  }
  check.across_draws = (sum_mean2 - sum_mean * sum_mean / draws) / (draws - 1);
  return check;
}

TEST(ProbeTexels, StrataVarianceOfNoisyLightIsItsTrueVariance) {
  // Noise of variance 1/12 on a gentle gradient: each cell's variance is the noise's, and
  // the gradient across a cell adds little.
  const VarianceCheck c = check_variance([](glm::vec2 p, Rng& rng) { return 1.0f + 0.2f * p.x + rng.next_float(); },
                                         24, 4000);
  EXPECT_NEAR(c.strata_estimate / c.across_draws, 1.0, 0.15) << c.strata_estimate << " vs " << c.across_draws;
  EXPECT_NEAR(c.spread_estimate / c.across_draws, 1.0, 0.15);
}

TEST(ProbeTexels, StrataVarianceCountsAnEdgeOnlyWhereItCrossesCells) {
  // A sill's edge at x = 0.37, bright beyond it: the stratified mean varies only by the
  // cells it crosses. The strata's estimate may err high (a pair across the edge) but stays
  // near the truth; the spread counts the whole step, many times the truth.
  const VarianceCheck c =
      check_variance([](glm::vec2 p, Rng&) { return p.x < 0.37f ? 1.0f : 10.0f; }, 24, 4000);
  EXPECT_GE(c.strata_estimate, 0.9 * c.across_draws) << c.strata_estimate << " vs " << c.across_draws;
  EXPECT_LE(c.strata_estimate, 3.0 * c.across_draws);
  EXPECT_GE(c.spread_estimate, 4.0 * c.strata_estimate) << c.spread_estimate;
}

TEST(ProbeTexels, StrataVarianceNeedsEnoughPairs) {
  Rng rng(5, 1);
  std::vector<glm::vec2> points;
  stratified_square(4, rng, &points);  // 2 x 2 cells: 2 pairs
  EXPECT_LT(stratified_mean_variance(points, {1.0f, 2.0f, 3.0f, 4.0f}, 8), 0.0);
  EXPECT_GE(stratified_mean_variance(points, {1.0f, 2.0f, 3.0f, 4.0f}, 2), 0.0);
  EXPECT_LT(stratified_mean_variance(points, {1.0f, 2.0f}, 2), 0.0);  // one value per point
}

TEST(ProbePlacement, OriginIsTheFirstSurfaceOffsetAlongItsNormalAndMasksFollowTheGBuffer) {
  // A box room with a ceiling light, a glass cube and an open top over one corner is not
  // needed: a floor, one emitting wall, a glass pane, and nothing elsewhere.
  scenes::Scene scene;
  const int floor_m = test::add_material(scene, test::make_material(glm::vec3(0.5f)));
  const int light_m = test::add_material(scene, test::make_emitter(glm::vec3(4.0f)));
  scenes::Material glass = test::make_material(glm::vec3(1.0f), 0.0f);
  glass.transmission_factor = 1.0f;
  const int glass_m = test::add_material(scene, glass);
  test::add_quad(scene, glm::vec3(-5, 0, 5), glm::vec3(10, 0, 0), glm::vec3(0, 0, -10), floor_m, "floor");
  // Wall at z = -3 facing +Z (towards the camera), emitting.
  test::add_quad(scene, glm::vec3(-5, 0, -3), glm::vec3(10, 0, 0), glm::vec3(0, 5, 0), light_m, "light wall");
  // Glass pane at x = +3 facing -X.
  test::add_quad(scene, glm::vec3(3, 0, 5), glm::vec3(0, 0, -10), glm::vec3(0, 5, 0), glass_m, "glass");
  const RenderScene rs(scene);
  CameraModel camera;
  camera.position = glm::vec3(0.2f, 1.5f, 0.1f);
  camera.width = 64;
  camera.height = 32;
  ProbeLayout layout;
  layout.grid_height = 16;
  layout.grid_width = 32;
  const float offset = 0.01f;
  const std::vector<ProbeSite> sites = place_probes(rs, camera, layout, offset);
  ASSERT_EQ(sites.size(), 512u);
  int counts[4] = {0, 0, 0, 0};
  for (int i = 0; i < layout.grid_height; ++i) {
    for (int j = 0; j < layout.grid_width; ++j) {
      const ProbeSite& s = sites[size_t(i) * layout.grid_width + j];
      ++counts[int(s.status)];
      // Grid of half the image: the corner shared by pixels (2i..2i+1, 2j..2j+1).
      const glm::vec2 pixel = probe_pixel_position(layout, camera, i, j);
      EXPECT_FLOAT_EQ(pixel.x, 2.0f * j + 1.0f);
      EXPECT_FLOAT_EQ(pixel.y, 2.0f * i + 1.0f);
      const glm::vec3 d = equirect_direction(glm::vec2((j + 0.5f) / 32, (i + 0.5f) / 16));
      if (!s.computed()) {
        EXPECT_EQ(s.origin, glm::vec3(0.0f));
        continue;
      }
      EXPECT_NEAR(glm::length(s.origin - s.surface), offset, 1e-6f);
      EXPECT_NEAR(glm::dot(glm::normalize(s.surface - camera.position), d), 1.0f, 1e-5f);
      EXPECT_LT(glm::dot(s.normal, d), 0.0f);  // the normal faces the camera
      if (d.y < -0.05f && std::abs(d.z / d.y) * 1.5f < 2.9f && std::abs(d.x / d.y) * 1.5f < 2.7f) {
        EXPECT_EQ(s.status, ProbeStatus::kValid) << i << "," << j;  // the floor, short of the wall and the pane
        EXPECT_NEAR(s.surface.y, 0.0f, 1e-5f);
        EXPECT_NEAR(s.origin.y, offset, 1e-5f);
      }
    }
  }
  EXPECT_GT(counts[int(ProbeStatus::kValid)], 0);
  EXPECT_GT(counts[int(ProbeStatus::kEmitter)], 0);
  EXPECT_GT(counts[int(ProbeStatus::kTransparent)], 0);
  EXPECT_GT(counts[int(ProbeStatus::kNothing)], 0);  // the open sky
}

TEST(ProbePlacement, AGapNarrowerThanTheOffsetHalvesIt) {
  scenes::Scene scene;
  const int m = test::add_material(scene, test::make_material());
  test::add_quad(scene, glm::vec3(-5, 0, 5), glm::vec3(10, 0, 0), glm::vec3(0, 0, -10), m, "floor");
  // A sheet 4 mm above the floor, facing down, with a hole... simply seen from below: the
  // camera sits between floor and sheet.
  test::add_quad(scene, glm::vec3(-5, 0.004f, -5), glm::vec3(10, 0, 0), glm::vec3(0, 0, 10), m, "sheet");
  const RenderScene rs(scene);
  CameraModel camera;
  camera.position = glm::vec3(0.0f, 0.002f, 0.0f);
  ProbeLayout layout;
  layout.grid_height = 4;
  layout.grid_width = 8;
  const std::vector<ProbeSite> sites = place_probes(rs, camera, layout, 0.01f);
  const ProbeSite& down = sites[3 * 8 + 4];  // a row below the horizon: sees the floor
  ASSERT_TRUE(down.valid());
  EXPECT_NEAR(down.offset, 0.002f, 1e-4f);
  EXPECT_GT(down.origin.y, 0.0f);
  EXPECT_LT(down.origin.y, 0.004f);
}

}  // namespace
}  // namespace phyir::render
