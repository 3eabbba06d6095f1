// Punctual lights in the probes: each light a probe's origin sees lands in the one texel its
// direction falls in, with the irradiance I falloff / d^2 (E for a directional light) spread
// over that texel's solid angle; hidden lights and lights outside a spot's cone add nothing.
// Expected values are computed here from the lights' definitions, not by DeltaLights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "phyir/render/effects.h"
#include "phyir/render/equirect.h"
#include "phyir/render/probe_renderer.h"
#include "punctual_deposit.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

constexpr int kH = 16, kW = 32;
const glm::vec3 kColor(1.0f, 0.5f, 0.25f);  // the lights' colour: channels differ

// A floor, and a board at y = 1.5 over x in [1, 2], z in [-0.5, 0.5] that hides the point
// light and the sun from the probe under it.
scenes::Scene deposit_scene() {
  scenes::Scene scene;
  const int m = test::add_material(scene, test::make_material(glm::vec3(0.5f)));
  test::add_quad(scene, glm::vec3(-5, 0, -5), glm::vec3(0, 0, 10), glm::vec3(10, 0, 0), m, "floor");
  test::add_quad(scene, glm::vec3(1, 1.5f, -0.5f), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), m, "board");
  using Type = scenes::PunctualLight::Type;
  scene.lights = {test::make_punctual_light(Type::Point, 3.0f, glm::vec3(1.5f, 2.5f, 0.0f), glm::vec3(0, -1, 0), 0.3f, 0.5f, kColor),
                  test::make_punctual_light(Type::Spot, 8.0f, glm::vec3(-1.0f, 2.0f, -1.0f), glm::vec3(0, -1, 0), 0.3f, 0.5f, kColor),
                  test::make_punctual_light(Type::Directional, 2.0f, glm::vec3(0.0f), glm::vec3(0.3f, -1.0f, 0.2f), 0.3f, 0.5f, kColor)};
  return scene;
}

ProbeSite site_at(const glm::vec3& origin) {
  ProbeSite s;
  s.surface = glm::vec3(origin.x, 0.0f, origin.z);
  s.normal = glm::vec3(0, 1, 0);
  s.origin = origin;
  s.offset = origin.y;
  s.status = ProbeStatus::kValid;
  return s;
}

// Row and column by the mapping's definition (core/equirect.h).
glm::ivec2 expected_texel(const glm::vec3& d) {
  double u = 0.5 + std::atan2(double(d.x), -double(d.z)) / (2.0 * M_PI);
  if (u >= 1.0) u -= 1.0;  // +Z itself is column 0
  const double v = std::acos(std::clamp(double(d.y), -1.0, 1.0)) / M_PI;
  return {std::min(int(v * kH), kH - 1), std::min(int(u * kW), kW - 1)};
}

// What a light sends to `origin` when nothing hides it: direction and irradiance.
glm::vec3 expected_irradiance(const scenes::PunctualLight& l, const glm::vec3& origin, glm::vec3* wi) {
  const glm::vec3 radiometric = l.color * (l.intensity / scenes::PunctualLight::kLumensPerWatt);
  if (l.type == scenes::PunctualLight::Type::Directional) {
    *wi = -l.direction;
    return radiometric;
  }
  const glm::vec3 d = l.position - origin;
  *wi = glm::normalize(d);
  float falloff = 1.0f;
  if (l.type == scenes::PunctualLight::Type::Spot) {
    const float angle = std::acos(glm::dot(l.direction, -*wi));
    if (angle > l.outer_cone_angle) falloff = 0.0f;
    EXPECT_TRUE(angle > l.outer_cone_angle || angle < l.inner_cone_angle) << "keep the test off the ramp";
  }
  return radiometric * falloff / glm::dot(d, d);
}

TEST(PunctualDeposit, EachVisibleLightLandsInItsTexelWithItsIrradiance) {
  const scenes::Scene scene = deposit_scene();
  const RenderScene rs(scene);
  ProbeLayout layout;
  layout.grid_height = 1, layout.grid_width = 3, layout.res_height = kH, layout.res_width = kW;
  // Probe 0 sees the point light and the sun and is outside the spot's cone; probe 1 is under
  // the board (point light and sun hidden, spot's cone missed); probe 2 is under the spot.
  const std::vector<ProbeSite> sites = {site_at(glm::vec3(0, 0.5f, 0)), site_at(glm::vec3(1.5f, 0.5f, 0)),
                                        site_at(glm::vec3(-0.95f, 0.5f, -1.1f))};
  const bool sees[3][3] = {{true, false, true}, {false, false, false}, {true, true, true}};
  Image mosaic(layout.mosaic_width(), layout.mosaic_height(), 3);
  const uint64_t rays = deposit_punctual_lights(rs, layout, sites, {0, 1, 2}, &mosaic);
  EXPECT_EQ(rays, 7u) << "one shadow ray per probe and light inside the spot's cone";

  for (int p = 0; p < 3; ++p) {
    Image expected(kW, kH, 3);
    for (size_t l = 0; l < scene.lights.size(); ++l) {
      glm::vec3 wi;
      const glm::vec3 e = expected_irradiance(scene.lights[l], sites[size_t(p)].origin, &wi);
      if (!sees[p][l]) continue;
      ASSERT_GT(e.x, 0.0f);
      const glm::ivec2 t = expected_texel(wi);
      for (int c = 0; c < 3; ++c)
        expected.at(t.y, t.x, c) += e[c] / float(equirect_texel_solid_angle(t.x, kW, kH));
    }
    for (int r = 0; r < kH; ++r)
      for (int c = 0; c < kW; ++c)
        for (int ch = 0; ch < 3; ++ch) {
          const float got = mosaic.at(p * kW + c, r, ch), want = expected.at(c, r, ch);
          ASSERT_NEAR(got, want, 1e-5f * std::max(1.0f, want)) << "probe " << p << " texel " << r << "," << c;
        }
  }
}

TEST(PunctualDeposit, TexelOfADirectionIsTheTexelWhoseDirectionsContainIt) {
  for (int r = 0; r < kH; ++r)
    for (int c = 0; c < kW; ++c)
      for (const glm::vec2 a : {glm::vec2(0.01f, 0.02f), glm::vec2(0.5f), glm::vec2(0.98f, 0.97f)}) {
        const glm::ivec2 t = probe_texel_of(probe_texel_direction(r, c, kH, kW, a), kH, kW);
        ASSERT_EQ(t, glm::ivec2(r, c));
      }
}

// The renderer adds them in both modes, and the probe integral gains exactly the lights'
// irradiance: sum of (on - off) x solid angle over a probe equals the sum over visible lights.
TEST(PunctualDeposit, BothModesAddTheLightsIrradianceToTheProbe) {
  const scenes::Scene scene = deposit_scene();
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  ASSERT_TRUE(effects.punctual_lights);
  for (ProbeMode mode : {ProbeMode::kPath, ProbeMode::kCache}) {
    ProbeSettings s;
    s.mode = mode;
    s.spp = 2;
    s.layout.grid_height = 1, s.layout.grid_width = 1, s.layout.res_height = kH, s.layout.res_width = kW;
    s.path.max_bounces = 2;
    s.cache.samples_per_cell = 16;
    s.progress = false;
    const std::vector<ProbeSite> site = {site_at(glm::vec3(0, 0.5f, 0))};
    const Image on = ProbeRenderer(rs, effects, s).render_at(site).mosaic;
    s.punctual_lights = false;
    const Image off = ProbeRenderer(rs, effects, s).render_at(site).mosaic;
    glm::dvec3 added(0.0);
    for (int r = 0; r < kH; ++r)
      for (int c = 0; c < kW; ++c)
        for (int ch = 0; ch < 3; ++ch) added[ch] += double(on.at(c, r, ch) - off.at(c, r, ch)) * equirect_texel_solid_angle(r, kW, kH);
    glm::vec3 wi, want(0.0f);
    want += expected_irradiance(scene.lights[0], site[0].origin, &wi);
    want += expected_irradiance(scene.lights[2], site[0].origin, &wi);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(added[ch], want[ch], 1e-4 * want[ch]) << probe_mode_name(mode);
  }
}

}  // namespace
}  // namespace phyir::render
