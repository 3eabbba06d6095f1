// glTF alpha coverage in light transport (docs/brdf.md, "Alpha coverage"): a BLEND surface
// of alpha a stops a fraction a of the rays that reach it and lets 1 - a through, for
// camera, path and shadow rays; its emission counts a times; MASK keeps its cutoff; the
// AOVs record the blended surface itself and mark it in mask_transparent. Each expectation
// is analytic; the scenes are chosen so that nothing else contributes.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>

#include "phyir/render/equirect.h"
#include "phyir/render/render_view.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

constexpr int kWidth = 64, kHeight = 32;

CameraModel panorama(const glm::vec3& position) {
  CameraModel c;
  c.position = position;
  c.width = kWidth;
  c.height = kHeight;
  return c;
}

RenderSettings settings(int spp, int max_bounces = 8) {
  RenderSettings s;
  s.spp = spp;
  s.seed = 11;
  s.progress = false;
  s.path.max_bounces = max_bounces;
  return s;
}

// A perfectly black surface (metal of base colour 0 reflects only at grazing Fresnel; seen
// from where nothing lights it, nothing), double-sided, with the given alpha mode.
scenes::Material black_sheet(float alpha, scenes::AlphaMode mode) {
  scenes::Material m = test::make_material(glm::vec3(0.0f), 1.0f, 1.0f, "sheet");
  m.base_color_factor.w = alpha;
  m.alpha_mode = mode;
  m.double_sided = true;
  return m;
}

// The camera at the origin looks at an emitting wall at z = -2 (radiance 1, facing +z);
// a sheet at z = -1 covers |x|, |y| < 0.5 in front of it. Nothing lights the camera's side
// of the sheet, so a pixel through the sheet reads exactly (1 - coverage) x 1.
scenes::Scene sheet_before_a_wall(const scenes::Material& sheet) {
  scenes::Scene scene;
  scene.source = "alpha_coverage_test";
  const int wall = test::add_material(scene, test::make_emitter(glm::vec3(1.0f)));
  test::add_quad(scene, glm::vec3(-4, -4, -2), glm::vec3(8, 0, 0), glm::vec3(0, 8, 0), wall, "wall");
  test::add_quad(scene, glm::vec3(-0.5f, -0.5f, -1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
                 test::add_material(scene, sheet), "sheet");
  return scene;
}

// Pixels whose centre ray crosses the sheet well inside its edges (the pixel's footprint
// stays on it), and pixels that see the wall beside the sheet.
struct PixelSets {
  std::vector<int> through, beside;
};

PixelSets classify_pixels() {
  PixelSets s;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec3 d = equirect_direction(glm::vec2((x + 0.5f) / kWidth, (y + 0.5f) / kHeight));
      if (!(d.z < -0.3f)) continue;
      const glm::vec2 at_sheet = glm::vec2(d.x, d.y) / -d.z;  // where the ray meets z = -1
      const float reach = std::max(std::abs(at_sheet.x), std::abs(at_sheet.y));
      if (reach < 0.35f) s.through.push_back(y * kWidth + x);
      if (reach > 0.7f && reach < 1.5f) s.beside.push_back(y * kWidth + x);
    }
  }
  return s;
}

double mean_of(const Image& image, const std::vector<int>& pixels) {
  double sum = 0.0;
  for (int p : pixels) sum += image.at(p % kWidth, p / kWidth, 1);
  return sum / double(pixels.size());
}

TEST(AlphaCoverage, BlendedSheetTransmitsOneMinusAlphaToTheCamera) {
  const PixelSets pixels = classify_pixels();
  ASSERT_GT(pixels.through.size(), 20u);
  ASSERT_GT(pixels.beside.size(), 20u);
  for (float alpha : {0.15f, 0.5f, 0.85f}) {
    const scenes::Scene scene = sheet_before_a_wall(black_sheet(alpha, scenes::AlphaMode::Blend));
    const RenderScene rs(scene);
    const RenderOutput out = render_view(rs, panorama(glm::vec3(0.0f)), settings(256));
    EXPECT_TRUE(out.effects.alpha_blending);
    EXPECT_FALSE(out.effects.alpha_masking);
    const Image color = out.film.color();
    // Each pixel's mean over 256 Bernoulli(1 - a) draws; the set's mean over ~100 pixels:
    // standard deviation below 0.004.
    EXPECT_NEAR(mean_of(color, pixels.through), 1.0 - alpha, 0.02) << "alpha " << alpha;
    EXPECT_NEAR(mean_of(color, pixels.beside), 1.0, 1e-4) << "alpha " << alpha;
    // The AOVs see the sheet itself, and mark it transparent.
    const int p = pixels.through.front();
    EXPECT_NEAR(out.film.aov("depth").at(p % kWidth, p / kWidth), 1.0f, 0.15f);
    EXPECT_EQ(out.film.aov("mask_transparent").at(p % kWidth, p / kWidth), 1.0f);
    const int q = pixels.beside.front();
    EXPECT_EQ(out.film.aov("mask_transparent").at(q % kWidth, q / kWidth), 0.0f);
  }
}

TEST(AlphaCoverage, MaskKeepsItsCutoffAndOpaqueIgnoresAlpha) {
  const PixelSets pixels = classify_pixels();
  struct Case {
    scenes::AlphaMode mode;
    float alpha;
    double through;
  };
  for (const Case c : {Case{scenes::AlphaMode::Mask, 0.4f, 1.0}, Case{scenes::AlphaMode::Mask, 0.6f, 0.0},
                       Case{scenes::AlphaMode::Opaque, 0.2f, 0.0}}) {
    const scenes::Scene scene = sheet_before_a_wall(black_sheet(c.alpha, c.mode));
    const RenderScene rs(scene);
    const RenderOutput out = render_view(rs, panorama(glm::vec3(0.0f)), settings(16));
    EXPECT_FALSE(out.effects.alpha_blending);
    EXPECT_EQ(out.effects.alpha_masking, c.mode == scenes::AlphaMode::Mask);
    // Black metal at near-normal incidence in the dark reflects nothing: exact values.
    EXPECT_NEAR(mean_of(out.film.color(), pixels.through), c.through, 1e-4) << c.alpha;
  }
}

TEST(AlphaCoverage, TexturedAlphaBlendsTexelByTexel) {
  // Alpha 0.25 on the sheet's left half (u < 0.5), 0.75 on its right half, in the base
  // colour texture; the factor's alpha is 1.
  scenes::Scene scene = sheet_before_a_wall(black_sheet(1.0f, scenes::AlphaMode::Blend));
  const int texture = test::add_texture(scene, 2, 1, {glm::vec4(0, 0, 0, 0.25f), glm::vec4(0, 0, 0, 0.75f)});
  scene.materials[1].base_color_texture.texture = texture;
  const RenderScene rs(scene);
  const Image color = render_view(rs, panorama(glm::vec3(0.0f)), settings(256)).film.color();
  std::vector<int> left, right;
  for (int p : classify_pixels().through) {
    const glm::vec3 d = equirect_direction(glm::vec2((p % kWidth + 0.5f) / kWidth, (p / kWidth + 0.5f) / kHeight));
    const float x = d.x / -d.z;
    if (x < -0.1f) left.push_back(p);
    if (x > 0.1f) right.push_back(p);
  }
  ASSERT_GT(left.size(), 8u);
  ASSERT_GT(right.size(), 8u);
  EXPECT_NEAR(mean_of(color, left), 0.75, 0.03);
  EXPECT_NEAR(mean_of(color, right), 0.25, 0.03);
}

TEST(AlphaCoverage, BlendedEmitterCountsAlphaOfItsEmission) {
  // A white floor lit only by a blended emitting panel above it: the floor under a panel of
  // emission 4 and alpha 0.25 is as bright as under an opaque panel of emission 1. Both
  // strategies of the MIS pair (the light sample and the BRDF ray that hits the panel with
  // probability alpha) must count alpha for that.
  auto floor_under = [](const glm::vec3& emission, float alpha) {
    scenes::Scene scene;
    scene.source = "alpha_coverage_test: panel";
    const int floor = test::add_material(scene, test::make_material(glm::vec3(0.8f)));
    test::add_quad(scene, glm::vec3(-2, 0, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4), floor, "floor");
    scenes::Material panel = test::make_emitter(emission, true);
    panel.base_color_factor.w = alpha;
    panel.alpha_mode = scenes::AlphaMode::Blend;
    test::add_quad(scene, glm::vec3(-0.5f, 1.0f, -0.5f), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1),
                   test::add_material(scene, panel), "panel");
    return scene;
  };
  const scenes::Scene blended = floor_under(glm::vec3(4.0f), 0.25f);
  const scenes::Scene opaque = floor_under(glm::vec3(1.0f), 1.0f);
  const RenderScene a(blended), b(opaque);
  // The camera below the panel looks at the floor (lower half of the panorama).
  const Image ia = render_view(a, panorama(glm::vec3(0, 0.5f, 0)), settings(256, 1)).film.color();
  const Image ib = render_view(b, panorama(glm::vec3(0, 0.5f, 0)), settings(256, 1)).film.color();
  double sa = 0.0, sb = 0.0;
  for (int y = kHeight * 3 / 4; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) sa += ia.at(x, y, 1), sb += ib.at(x, y, 1);
  ASSERT_GT(sb, 0.0);
  EXPECT_NEAR(sa / sb, 1.0, 0.03);
}

TEST(AlphaCoverage, ShadowOfABlendedSheetUnderAPointLightIsOneMinusAlpha) {
  // A point light 2 m above a white floor, a black sheet of alpha a 1 m above the floor
  // under it. Direct light only (max_bounces 1): the floor below the sheet receives
  // exactly (1 - a) of the unshadowed irradiance.
  const float alpha = 0.3f;
  scenes::Scene scene;
  scene.source = "alpha_coverage_test: shadow";
  const float albedo = 0.8f;
  const int floor = test::add_material(scene, test::make_material(glm::vec3(albedo)));
  test::add_quad(scene, glm::vec3(-3, 0, 3), glm::vec3(6, 0, 0), glm::vec3(0, 0, -6), floor, "floor");
  test::add_quad(scene, glm::vec3(-0.6f, 1.0f, -0.6f), glm::vec3(1.2f, 0, 0), glm::vec3(0, 0, 1.2f),
                 test::add_material(scene, black_sheet(alpha, scenes::AlphaMode::Blend)), "sheet");
  const float watts = 4.0f;  // W/sr
  scene.lights.push_back(test::make_point_light(watts, glm::vec3(0, 2, 0)));
  const RenderScene rs(scene);
  const glm::vec3 eye(0, 0.5f, 0);
  const Image color = render_view(rs, panorama(eye), settings(256, 1)).film.color();
  double sum_ratio = 0.0, sum_ratio2 = 0.0;
  int n = 0;
  for (int y = kHeight / 2; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec3 d = equirect_direction(glm::vec2((x + 0.5f) / kWidth, (y + 0.5f) / kHeight));
      if (!(d.y < -0.2f)) continue;
      const glm::vec3 p = eye + d * (eye.y / -d.y);  // the floor point
      const glm::vec3 to_light = glm::vec3(0, 2, 0) - p;
      const float r2 = glm::dot(to_light, to_light);
      const float cosine = to_light.y / std::sqrt(r2);
      const glm::vec3 at_sheet = p + to_light * (1.0f / 2.0f);  // where the light's ray crosses y = 1
      const bool shadowed = std::abs(at_sheet.x) < 0.5f && std::abs(at_sheet.z) < 0.5f;
      const bool clear = std::abs(at_sheet.x) > 0.7f || std::abs(at_sheet.z) > 0.7f;
      const double unshadowed = double(albedo) / M_PI * watts * cosine / r2;
      const double got = color.at(x, y, 1);
      if (clear) EXPECT_NEAR(got, unshadowed, 0.02 * unshadowed) << x << "," << y;
      if (shadowed) sum_ratio += got / unshadowed, sum_ratio2 += (got / unshadowed) * (got / unshadowed), ++n;
    }
  }
  ASSERT_GT(n, 30);
  const double mean = sum_ratio / n, spread = std::sqrt(std::max(0.0, sum_ratio2 / n - mean * mean));
  std::printf("[alpha] shadow of a sheet of alpha %.2f at 256 spp: %.4f of the unshadowed irradiance, "
              "pixel-to-pixel spread %.4f\n", alpha, mean, spread);
  EXPECT_NEAR(mean, 1.0 - alpha, 0.02);
}

TEST(AlphaCoverage, SameSeedSameImageWhateverTheThreadCount) {
  const scenes::Scene scene = sheet_before_a_wall(black_sheet(0.5f, scenes::AlphaMode::Blend));
  const RenderScene rs(scene);
  Image one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = render_view(rs, panorama(glm::vec3(0.0f)), settings(8)).film.color();
  }
  two = render_view(rs, panorama(glm::vec3(0.0f)), settings(8)).film.color();
  EXPECT_EQ(one.pixels, two.pixels);
}

TEST(AlphaCoverage, AnOpaqueSceneRunsNoAlphaCode) {
  const scenes::Scene scene = sheet_before_a_wall(black_sheet(1.0f, scenes::AlphaMode::Opaque));
  const Effects e = analyse_effects(scene, false);
  EXPECT_FALSE(e.alpha_blending);
  EXPECT_FALSE(e.alpha_masking);
  const nlohmann::json j = e.to_json();
  EXPECT_EQ(j.at("alpha_blending"), false);
  EXPECT_EQ(j.at("alpha_masking"), false);
}

}  // namespace
}  // namespace phyir::render
