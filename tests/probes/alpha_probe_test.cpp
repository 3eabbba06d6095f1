// Probes see through blended surfaces as the path tracer does (docs/brdf.md, "Alpha
// coverage"): a probe texel that looks through a black sheet of alpha a at an emitting wall
// reads (1 - a) of the wall's radiance, in both modes; texels beside the sheet read the
// wall exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "phyir/render/probe_grid.h"
#include "single_probe.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

// An emitting wall (radiance 1, facing +z) at z = -2 and, in front of it at z = -1, a black
// double-sided sheet of alpha `alpha` covering |x|, |y| < 0.5.
scenes::Scene sheet_before_a_wall(float alpha) {
  scenes::Scene scene;
  scene.source = "alpha_probe_test";
  const int wall = test::add_material(scene, test::make_emitter(glm::vec3(1.0f)));
  test::add_quad(scene, glm::vec3(-4, -4, -2), glm::vec3(8, 0, 0), glm::vec3(0, 8, 0), wall, "wall");
  scenes::Material sheet = test::make_material(glm::vec3(0.0f), 1.0f, 1.0f, "sheet");
  sheet.base_color_factor.w = alpha;
  sheet.alpha_mode = scenes::AlphaMode::Blend;
  sheet.double_sided = true;
  test::add_quad(scene, glm::vec3(-0.5f, -0.5f, -1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
                 test::add_material(scene, sheet), "sheet");
  return scene;
}

TEST(AlphaProbe, TexelsThroughABlendedSheetReadOneMinusAlpha) {
  const int h = 16, w = 32;
  const float alpha = 0.4f;
  const scenes::Scene scene = sheet_before_a_wall(alpha);
  for (ProbeMode mode : {ProbeMode::kPath, ProbeMode::kCache}) {
    const Image probe = render_single(scene, glm::vec3(0.0f), settings_for(mode, 256, h, w));
    double through = 0.0, beside = 0.0;
    int n_through = 0, n_beside = 0;
    for (int i = 0; i < h; ++i) {
      for (int j = 0; j < w; ++j) {
        // The texel's corners all on the sheet, or all beside it on the wall.
        float lo = 1e9f, hi = 0.0f;
        bool ahead = true;
        for (float a : {0.0f, 1.0f})
          for (float b : {0.0f, 1.0f}) {
            const glm::vec3 d = probe_texel_direction(i, j, h, w, glm::vec2(a, b));
            ahead &= d.z < -0.2f;
            const float reach = std::max(std::abs(d.x), std::abs(d.y)) / std::max(-d.z, 1e-3f);
            lo = std::min(lo, reach), hi = std::max(hi, reach);
          }
        if (!ahead) continue;
        if (hi < 0.5f) through += probe.at(j, i, 1), ++n_through;
        if (lo > 0.5f && hi < 2.0f) beside += probe.at(j, i, 1), ++n_beside;
      }
    }
    ASSERT_GT(n_through, 2) << probe_mode_name(mode);
    ASSERT_GT(n_beside, 4) << probe_mode_name(mode);
    EXPECT_NEAR(through / n_through, 1.0 - alpha, 0.05) << probe_mode_name(mode);
    EXPECT_NEAR(beside / n_beside, 1.0, 0.01) << probe_mode_name(mode);
  }
}

}  // namespace
}  // namespace phyir::render
