// The foot correction (foot_correction.h): which texels face away from a probe's front (never
// one with a direction in front), the probe's measurement of the irradiance at its foot
// (uniform light integrates to pi), where a correction applies (the foot's surface, in full
// within a cell, fading to none at three; never below zero; its measurement's variance in
// place of the cache's), and what it is for: with a
// deliberately noisy cache, the texels probes see of their own floor come far closer to a
// converged cache's with it than without.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "phyir/render/effects.h"
#include "phyir/render/equirect.h"
#include "foot_correction.h"
#include "phyir/render/probe_renderer.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "test_scenes.h"
#include "sanitizer_skip.h"

namespace phyir::render {
namespace {

TEST(TexelCones, TexelsFacingAwayHaveNoDirectionInFrontAndAxisAlignedHalvesAreFound) {
  constexpr int kH = 16, kW = 32, kGrid = 9;
  const TexelCones cones(kH, kW);
  const glm::vec3 normals[] = {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0),
                               glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f)), glm::normalize(glm::vec3(-0.9f, 0.1f, 0.2f))};
  for (const glm::vec3& n : normals) {
    int away = 0;
    for (int t = 0; t < kH * kW; ++t) {
      const ProbeTexel texel(t / kW, t % kW, kH, kW);
      float highest = -1.0f;  // the largest d . n over a 9 x 9 grid of the texel, edges included
      for (int a = 0; a < kGrid; ++a)
        for (int b = 0; b < kGrid; ++b)
          highest = std::max(highest, glm::dot(texel.direction(glm::vec2(a, b) / float(kGrid - 1)), n));
      if (!cones.faces_away(t, n)) continue;
      ++away;
      EXPECT_LT(highest, 0.0f) << "texel " << t << " has a direction in front of " << n.x << "," << n.y << "," << n.z;
    }
    // At least the hemisphere less the texels touching its horizon (for a wall, the columns
    // beside it and the rows round the poles, which lie in the wall's plane): over a third.
    EXPECT_GT(away, kH * kW / 3) << n.x << "," << n.y << "," << n.z;
  }
  // Looking up, rows 9..15 lie wholly below the horizon; row 8 touches it.
  for (int t = 0; t < kH * kW; ++t) EXPECT_EQ(cones.faces_away(t, glm::vec3(0, 1, 0)), t / kW >= 9) << t;
}

TEST(FootIrradiance, UniformRadianceIntegratesToPiAndEmissionCountsAsDirect) {
  constexpr int kH = 16, kW = 32, kN = 64;
  const glm::vec3 n = glm::normalize(glm::vec3(0.2f, 0.9f, -0.3f));
  FootIrradiance measured(n);
  Rng rng(7, 1);
  for (int t = 0; t < kH * kW; ++t) {
    const ProbeTexel texel(t / kW, t % kW, kH, kW);
    double cos_mean = 0.0;
    for (int s = 0; s < kN; ++s) cos_mean += measured.cosine(texel.direction(rng.next_2d()));
    cos_mean /= kN;
    // Radiance 1 everywhere, a quarter of it emitted by a light seen first.
    measured.add_texel(glm::vec3(float(cos_mean)), glm::vec3(0.25f * float(cos_mean)),
                       equirect_texel_solid_angle(t / kW, kW, kH));
  }
  const float pi = 3.14159265f;
  EXPECT_NEAR(measured.indirect().x + measured.direct().x, pi, 0.01f * pi);
  EXPECT_NEAR(measured.direct().y, 0.25f * pi, 0.01f * pi);
  EXPECT_NEAR(measured.indirect().z, 0.75f * pi, 0.01f * pi);
}

// A 4 x 4 m floor under a square light, and a cache over the middle of it.
struct FloorCache {
  scenes::Scene scene;
  std::unique_ptr<RenderScene> render_scene;
  std::unique_ptr<RadianceCache> cache;

  FloorCache() {
    const int floor_m = test::add_material(scene, test::make_material(glm::vec3(0.5f), 1.0f, 0.0f));
    const int light_m = test::add_material(scene, test::make_emitter(glm::vec3(4.0f)));
    test::add_quad(scene, glm::vec3(-2, 0, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4), floor_m, "floor");
    test::add_quad(scene, glm::vec3(-0.15f, 1.0f, -0.15f), glm::vec3(0.3f, 0, 0), glm::vec3(0, 0, 0.3f), light_m, "light");
    render_scene = std::make_unique<RenderScene>(scene);
    RadianceCacheSettings settings;
    settings.samples_per_cell = 16;
    cache = std::make_unique<RadianceCache>(*render_scene, analyse_effects(scene, false), PathSettings{2, 3}, settings);
    RadianceCache::Collector collector;
    uint64_t priority = 0;
    for (float x = -0.5f; x <= 0.5f; x += 0.01f)
      for (float z = -0.5f; z <= 0.5f; z += 0.01f)
        collector.offer(*cache, CachePoint{glm::vec3(x, 0, z), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)}, mix64(++priority));
    PathCounters counters;
    cache->build({&collector}, &counters);
  }
};

TEST(FootCorrection, TheMeasurementsVarianceTakesTheCachesPlaceInTheCorrectionsShare) {
  const FloorCache floor;
  ProbeSite site;
  site.surface = glm::vec3(0.3f, 0.0f, 0.2f);
  site.normal = glm::vec3(0, 1, 0);
  site.origin = site.surface + 0.01f * site.normal;
  site.status = ProbeStatus::kValid;
  CachedIrradiance at_foot;
  ASSERT_TRUE(floor.cache->interpolate(CachePoint{site.surface, site.normal, site.normal}, &at_foot));
  EXPECT_GT(at_foot.direct_variance, 0.0f) << "16 light samples a cell (no indirect light: a floor alone)";
  EXPECT_GT(at_foot.block, 0u);
  // Two texels of solid angles 0.5 and 0.25 with variances 0.04 and 0.08 (cosine-weighted).
  const glm::vec3 total = at_foot.indirect + at_foot.direct;
  FootIrradiance m(site.normal);
  m.add_texel(1.2f * total, 1.2f * at_foot.direct, 0.5f, 0.04f);
  m.add_texel(glm::vec3(0.0f), glm::vec3(0.0f), 0.25f, 0.08f);
  const float v = 0.25f * 0.04f + 0.0625f * 0.08f;
  EXPECT_FLOAT_EQ(m.variance(), v);
  const FootCorrection foot = FootCorrection::measure(*floor.cache, site, m);
  ASSERT_TRUE(foot.active());
  // At the foot the correction holds in full: the lookup's variance is the measurement's.
  CachedIrradiance E = at_foot;
  E.indirect_variance = 5.0f;
  E.direct_variance = 7.0f;
  E.block = 12;
  foot.apply(site.surface, site.normal, &E);
  EXPECT_NEAR(E.indirect_variance, v, 1e-6f);
  EXPECT_EQ(E.direct_variance, 0.0f);
  EXPECT_EQ(E.block, FootCorrection::kFootBlock);
  // Two cells out its share is a half: a quarter of each variance, and the block still the foot's.
  E = at_foot;
  E.indirect_variance = 4.0f;
  E.direct_variance = 2.0f;
  E.block = 12;
  foot.apply(site.surface + glm::vec3(2.0f * floor.cache->settings().cell_size, 0, 0), site.normal, &E);
  EXPECT_NEAR(E.indirect_variance, 1.0f + 0.25f * v, 1e-5f);
  EXPECT_NEAR(E.direct_variance, 0.5f, 1e-6f);
  EXPECT_EQ(E.block, FootCorrection::kFootBlock);
  // Beyond its reach nothing changes.
  E = at_foot;
  foot.apply(site.surface + glm::vec3(3.5f * floor.cache->settings().cell_size, 0, 0), site.normal, &E);
  EXPECT_EQ(E.indirect_variance, at_foot.indirect_variance);
  EXPECT_EQ(E.block, at_foot.block);
}

TEST(FootCorrection, ScalesLookupsOnTheFootsSurfaceInFullWithinACellAndFadesOutAtThree) {
  const FloorCache floor;
  ProbeSite site;
  site.surface = glm::vec3(0.3f, 0.0f, 0.2f);  // far enough from the light for cached direct light
  site.normal = glm::vec3(0, 1, 0);
  site.origin = site.surface + 0.01f * site.normal;
  site.status = ProbeStatus::kValid;
  CachedIrradiance at_foot;
  ASSERT_TRUE(floor.cache->interpolate(CachePoint{site.surface, site.normal, site.normal}, &at_foot));
  ASSERT_TRUE(at_foot.has_direct);
  // A measurement of twice the cache's light at the foot (as one texel of solid angle 1).
  const glm::vec3 total = at_foot.indirect + at_foot.direct;
  FootIrradiance twice(site.normal);
  twice.add_texel(2.0f * total, 2.0f * at_foot.direct, 1.0f);
  const FootCorrection measured = FootCorrection::measure(*floor.cache, site, twice);
  ASSERT_TRUE(measured.active());
  EXPECT_NEAR(measured.difference().y, total.y, 1e-4f * total.y);
  // Less a common difference of a quarter of that: the correction is the other three quarters.
  const FootCorrection foot = measured.less(0.25f * total);
  const float shift = 0.75f * total.x;

  const float cell = floor.cache->settings().cell_size;
  auto scaled = [&](const glm::vec3& offset, const glm::vec3& normal) {
    CachedIrradiance E;
    E.indirect = glm::vec3(1.0f);
    E.direct = glm::vec3(0.5f);
    E.has_direct = true;
    foot.apply(site.surface + offset, normal, &E);
    return E;
  };
  const glm::vec3 up(0, 1, 0);
  EXPECT_NEAR(scaled(glm::vec3(0.9f * cell, 0, 0), up).indirect.x, 1.0f + shift, 1e-4f);        // within a cell: in full
  EXPECT_NEAR(scaled(glm::vec3(0, 0, 2.0f * cell), up).indirect.x, 1.0f + 0.5f * shift, 1e-4f);  // half way out: half
  EXPECT_NEAR(scaled(glm::vec3(0, 0, 2.0f * cell), up).direct.x, 0.5f, 1e-6f);                   // direct kept
  EXPECT_NEAR(scaled(glm::vec3(3.1f * cell, 0, 0), up).indirect.x, 1.0f, 1e-6f);                 // beyond three cells: none
  EXPECT_NEAR(scaled(glm::vec3(0, 0.6f * cell, 0), up).indirect.x, 1.0f, 1e-6f);                 // off the foot's plane
  EXPECT_NEAR(scaled(glm::vec3(0), glm::vec3(1, 0, 0)).indirect.x, 1.0f, 1e-6f);                 // another surface
  CachedIrradiance near_light;  // no cached direct light: another kind of value, left alone
  near_light.indirect = glm::vec3(1.0f);
  foot.apply(site.surface, up, &near_light);
  EXPECT_EQ(near_light.indirect.x, 1.0f);
  // A shift below zero takes the indirect part to 0 and the rest off the direct part.
  const FootCorrection darker = measured.less(measured.difference() + glm::vec3(1.2f));
  CachedIrradiance E;
  E.indirect = glm::vec3(1.0f);
  E.direct = glm::vec3(0.5f);
  E.has_direct = true;
  darker.apply(site.surface, up, &E);
  EXPECT_EQ(E.indirect.x, 0.0f);
  EXPECT_NEAR(E.direct.x, 0.3f, 1e-5f);
  // The mean of d and d - 1 (the inactive one left out), to rounding.
  EXPECT_NEAR(FootCorrection::common_difference({measured, FootCorrection(), measured.less(glm::vec3(1.0f))}).x,
              measured.difference().x - 0.5f, 1e-6f);

  // A measurement that cannot be the same light (10x) is not used; nor is a foot with no cell.
  FootIrradiance tenfold(site.normal);
  tenfold.add_texel(10.0f * total, 10.0f * at_foot.direct, 1.0f);
  EXPECT_FALSE(FootCorrection::measure(*floor.cache, site, tenfold).active());
  ProbeSite elsewhere = site;
  elsewhere.surface = glm::vec3(1.5f, 0.0f, 1.5f);
  EXPECT_FALSE(FootCorrection::measure(*floor.cache, elsewhere, twice).active());
}

// The mean of probe k's texels wholly below the horizon (its own floor).
double floor_texels_mean(const Image& mosaic, int k) {
  double sum = 0.0;
  for (int r = 9; r < 16; ++r)
    for (int c = 0; c < 32; ++c)
      for (int ch = 0; ch < 3; ++ch) sum += mosaic.at(k * 32 + c, r, ch);
  return sum / (7 * 32 * 3);
}

// A small closed room lit by a ceiling panel, and 9 x 9 probes 1 cm above its floor, 15 cm
// apart.
scenes::Scene small_lit_room() {
  scenes::Scene scene =
      test::make_box_room(glm::vec3(-0.8f, 0.0f, -0.8f), glm::vec3(0.8f, 1.5f, 0.8f), test::make_material(glm::vec3(0.6f), 0.8f, 0.0f));
  test::add_quad(scene, glm::vec3(-0.2f, 1.45f, -0.2f), glm::vec3(0.4f, 0, 0), glm::vec3(0, 0, 0.4f),
                 test::add_material(scene, test::make_emitter(glm::vec3(8.0f))), "light");
  return scene;
}

constexpr int kProbes = 81;

std::vector<ProbeSite> floor_sites() {
  std::vector<ProbeSite> sites;
  for (int k = 0; k < kProbes; ++k) {
    ProbeSite site;
    site.surface = glm::vec3(-0.6f + 0.15f * float(k % 9), 0.0f, -0.6f + 0.15f * float(k / 9));
    site.normal = glm::vec3(0, 1, 0);
    site.origin = site.surface + 0.01f * site.normal;
    site.offset = 0.01f;
    site.status = ProbeStatus::kValid;
    sites.push_back(site);
  }
  return sites;
}

ProbeSettings floor_settings(int spp, int cache_spp, uint64_t seed, bool correct) {
  ProbeSettings s;
  s.spp = spp;
  s.layout.grid_height = 1;
  s.layout.grid_width = kProbes;
  s.layout.res_height = 16;
  s.layout.res_width = 32;
  s.seed = seed;
  s.progress = false;
  s.cache.samples_per_cell = cache_spp;
  s.sharing.radius = 0;
  s.correct_foot = correct;
  s.punctual_lights = false;  // the probes' own floor is compared; their lights' texels are exact
  return s;
}

// The RMS over the probes of their own floor's error, with and without the correction, on a
// cache of 4 estimates per cell; the reference is the same renderer with 256 estimates.
struct OwnFloorError {
  double with = 0.0, without = 0.0;
  uint64_t corrected = 0;
};

OwnFloorError own_floor_error(const scenes::Scene& scene) {
  const RenderScene rs(scene);
  const std::vector<ProbeSite> sites = floor_sites();
  const Effects effects = analyse_effects(scene, false);
  const Image reference = ProbeRenderer(rs, effects, floor_settings(16, 256, 1, false)).render_at(sites).mosaic;
  const ProbeOutput with = ProbeRenderer(rs, effects, floor_settings(8, 4, 2, true)).render_at(sites);
  const ProbeOutput without = ProbeRenderer(rs, effects, floor_settings(8, 4, 2, false)).render_at(sites);
  EXPECT_EQ(without.stats.foot_corrections, 0u);
  double square_with = 0.0, square_without = 0.0;
  for (int k = 0; k < kProbes; ++k) {
    const double ref = floor_texels_mean(reference, k);
    square_with += std::pow(floor_texels_mean(with.mosaic, k) / ref - 1.0, 2);
    square_without += std::pow(floor_texels_mean(without.mosaic, k) / ref - 1.0, 2);
  }
  return {std::sqrt(square_with / kProbes), std::sqrt(square_without / kProbes), with.stats.foot_corrections};
}

TEST(ProbeFootCorrection, WithANoisyCacheTheProbesOwnFloorIsFarCloserToAConvergedCache) {
  PHYIR_SKIP_UNDER_SANITIZERS("FootCorrection.* and FootIrradiance.*");
  const scenes::Scene scene = small_lit_room();
  const OwnFloorError e = own_floor_error(scene);
  EXPECT_EQ(e.corrected, uint64_t(kProbes));
  std::printf("own floor against a converged cache over %d probes: RMS %.2f%% with the correction, %.2f%% without\n",
              kProbes, 100 * e.with, 100 * e.without);
  EXPECT_LT(e.with, 0.5 * e.without);
  EXPECT_LT(e.with, 0.02);

  // With fewer probes than the common difference needs, none is corrected.
  std::vector<ProbeSite> sites = floor_sites();
  sites.resize(9);
  ProbeSettings few = floor_settings(4, 4, 2, true);
  few.layout.grid_width = 9;
  EXPECT_EQ(ProbeRenderer(RenderScene(scene), analyse_effects(scene, false), few).render_at(sites).stats.foot_corrections,
            0u);
}

// The same room with a spot light on part of the floor: no texel holds a punctual light, so
// the probe's measurement must be compared with the cache's light without it. (Compared with
// a cache whose direct light held the spot, the lit probes measured far less than their cache
// and the rest, through the common difference, far more.)
TEST(ProbeFootCorrection, APunctualLightOnPartOfTheFloorDoesNotSkewTheCorrection) {
  PHYIR_SKIP_UNDER_SANITIZERS("FootCorrection.* and FootIrradiance.*");
  scenes::Scene scene = small_lit_room();
  scenes::PunctualLight spot;
  spot.type = scenes::PunctualLight::Type::Spot;
  spot.intensity = 1.0f * scenes::PunctualLight::kLumensPerWatt;
  spot.position = glm::vec3(-0.5f, 1.3f, -0.5f);
  spot.direction = glm::vec3(0, -1, 0);
  spot.inner_cone_angle = 0.2f;
  spot.outer_cone_angle = 0.3f;
  scene.lights = {spot};
  const OwnFloorError e = own_floor_error(scene);
  std::printf("own floor under a spot over %d probes: RMS %.2f%% with the correction, %.2f%% without\n", kProbes,
              100 * e.with, 100 * e.without);
  EXPECT_GT(e.corrected, uint64_t(kProbes / 2));
  EXPECT_LT(e.with, 0.5 * e.without);
  EXPECT_LT(e.with, 0.02);
}

}  // namespace
}  // namespace phyir::render
