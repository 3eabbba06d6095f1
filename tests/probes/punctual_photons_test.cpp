// Photons round point and spot lights and from the sun (punctual_photons.h): they and a
// texel's own directions split one integral, the lights' diffuse light at the texel's first
// hits, by the same rule.
// The photons' share of a texel is checked against that share integrated here by brute force
// (thousands of directions per texel through the estimator's own functions), and whole probes
// against the path mode, with and without photons.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/effects.h"
#include "phyir/render/equirect.h"
#include "phyir/render/probe_renderer.h"
#include "phyir/render/streams.h"
#include "punctual_photons.h"
#include "sanitizer_skip.h"
#include "single_probe.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

constexpr int kH = 16, kW = 32;

// A grey room, a bulb 4 cm under its ceiling, a board 30 cm under it that hides part of the
// ceiling's lit disc from the floor, and a spot lighting a wall from 30 cm.
scenes::Scene bulb_room() {
  scenes::Scene scene =
      test::make_box_room({-2.0f, 0.0f, -1.5f}, {2.0f, 2.6f, 1.5f}, test::make_material(glm::vec3(0.6f), 0.6f, 0.0f));
  const int board = test::add_material(scene, test::make_material(glm::vec3(0.3f), 0.8f, 0.0f));
  test::add_quad(scene, glm::vec3(0.3f, 2.3f, -0.1f), glm::vec3(0.3f, 0, 0), glm::vec3(0, 0, 0.3f), board, "board");
  using Type = scenes::PunctualLight::Type;
  const glm::vec3 warm(1.0f, 0.8f, 0.6f);
  scene.lights = {test::make_punctual_light(Type::Point, 2.0f, glm::vec3(0.3f, 2.56f, 0.2f), glm::vec3(0, -1, 0), 0.4f, 0.6f, warm),
                  test::make_punctual_light(Type::Spot, 4.0f, glm::vec3(-1.7f, 1.2f, -0.5f), glm::vec3(-1, 0.1f, 0), 0.4f, 0.6f, warm)};
  return scene;
}

// A grey room lit by the sun alone, through a 1 m square hole in its ceiling: a sun patch on
// its floor, its rim sharp.
scenes::Scene skylight_room() {
  scenes::Scene scene =
      test::make_box_room({-2.0f, 0.0f, -1.5f}, {2.0f, 2.6f, 1.5f}, test::make_material(glm::vec3(0.6f), 0.6f, 0.0f));
  scenes::Mesh ceiling;  // facing down, round the hole x, z in [-0.5, 0.5]
  ceiling.name = "ceiling";
  const float y = 2.6f;
  test::append_quad(ceiling, {-2.0f, y, -1.5f}, {4.0f, 0, 0}, {0, 0, 1.0f});
  test::append_quad(ceiling, {-2.0f, y, 0.5f}, {4.0f, 0, 0}, {0, 0, 1.0f});
  test::append_quad(ceiling, {-2.0f, y, -0.5f}, {1.5f, 0, 0}, {0, 0, 1.0f});
  test::append_quad(ceiling, {0.5f, y, -0.5f}, {1.5f, 0, 0}, {0, 0, 1.0f});
  ceiling.material = scene.meshes[3].material;
  scene.meshes[3] = ceiling;
  scene.lights = {test::make_punctual_light(scenes::PunctualLight::Type::Directional, 5.0f, glm::vec3(0.0f),
                                            glm::vec3(0.35f, -1.0f, 0.25f))};
  return scene;
}

// The lights' diffuse light at the first hit of `direction` from `origin`, the part the
// photons take there: what TexelEstimator leaves out (punctual_light's diffuse share).
glm::vec3 taken_part(const RenderScene& rs, const PunctualPhotons& photons, const glm::vec3& origin,
                     const glm::vec3& direction, float solid_angle) {
  SurfaceInteraction si;
  if (!rs.trace(Ray{origin, direction}, &si)) return glm::vec3(0.0f);
  float shares[PunctualPhotons::kMaxLights], rest[PunctualPhotons::kMaxLights];
  if (!photons.shares(origin, si.position, si.geometric_normal, solid_angle, shares)) return glm::vec3(0.0f);
  for (int i = 0; i < PunctualPhotons::kMaxLights; ++i) rest[i] = 1.0f - shares[i];
  ShadingPoint x = shading_point(si, -direction);
  if (!(x.wo.z >= kMinCosine)) return glm::vec3(0.0f);
  x.brdf = clamped(si.brdf);
  PathCounters c;
  return Fd_Lambert(x.brdf.base_color, x.brdf.metalness) * punctual_light(rs, x, Lobes::kCosine, &c, rest);
}

struct ProbeAt {
  const char* name;
  glm::vec3 origin, normal;
};

// The photons' share of each probe's texels, gathered (16 draws), against the integral the
// directions leave out, by brute force (48 x 48 directions per texel).
void expect_share_is_the_integral_left_out(const scenes::Scene& scene, int per_light, size_t min_photons,
                                           const std::vector<ProbeAt>& probes) {
  const RenderScene rs(scene);
  uint64_t rays = 0;
  const PunctualPhotons photons(rs, per_light, 4, scene.bounds, 3, &rays);
  ASSERT_GT(photons.size(), min_photons);
  for (const ProbeAt& probe : probes) {
    // The photons' estimate is exact where nothing hides them; where an edge hides some,
    // the sampling of the texel's photons is random: 16 draws of it, averaged.
    std::vector<glm::vec3> radiance(kH * kW, glm::vec3(0.0f)), one, one_cos;
    uint64_t shadow_rays = 0;
    const int draws = 16;
    for (uint64_t key = 0; key < draws; ++key) {
      photons.gather(probe.origin, probe.normal, kH, kW, mix64(key), &one, &one_cos, &shadow_rays);
      for (size_t t = 0; t < one.size(); ++t) radiance[t] += one[t] / float(draws);
    }
    shadow_rays /= draws;
    double got_total = 0.0, want_total = 0.0, worst = 0.0, brightest = 0.0;
    int texels_with_photons = 0;
    for (int r = 0; r < kH; ++r) {
      const float solid_angle = equirect_texel_solid_angle(r, kW, kH);
      for (int c = 0; c < kW; ++c) {
        glm::dvec3 sum(0.0);
        const int n = 48;
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b) {
            const glm::vec2 u((float(a) + 0.5f) / float(n), (float(b) + 0.5f) / float(n));
            sum += glm::dvec3(taken_part(rs, photons, probe.origin, probe_texel_direction(r, c, kH, kW, u), solid_angle));
          }
        const double want = luminance(glm::vec3(sum / double(n * n)));
        const double got = luminance(radiance[size_t(r * kW + c)]);
        texels_with_photons += got > 0.0;
        got_total += got * solid_angle, want_total += want * solid_angle;
        brightest = std::max(brightest, want);
        worst = std::max(worst, std::abs(got - want));
      }
    }
    std::printf("[ %s ] photons' share %.5f, brute force %.5f (%+.2f%%); %d texels, %llu shadow rays a draw; worst "
                "texel off by %.3f of the brightest\n",
                probe.name, got_total, want_total, 100.0 * (got_total / want_total - 1.0), texels_with_photons,
                static_cast<unsigned long long>(shadow_rays), worst / brightest);
    ASSERT_GT(want_total, 0.0) << probe.name << ": the test must put photons to work";
    EXPECT_NEAR(got_total / want_total, 1.0, 0.03) << probe.name;
    EXPECT_LT(worst, 0.1 * brightest) << probe.name;
  }
}

TEST(PunctualPhotons, TheirShareOfEachTexelIsTheIntegralTheDirectionsLeaveOut) {
  PHYIR_SKIP_UNDER_SANITIZERS("PunctualPhotons.TakeNothingWhereNoneAreSent");
  expect_share_is_the_integral_left_out(bulb_room(), 65536, 60000,
                                        {{"on the floor under the bulb", {0.0f, 0.01f, 0.0f}, {0, 1, 0}},
                                         {"on the ceiling 20 cm from the bulb", {0.5f, 2.59f, 0.1f}, {0, -1, 0}},
                                         {"on the wall the spot lights", {-1.99f, 1.0f, -0.2f}, {1, 0, 0}}});
}

// The same for the sun's photons, through a skylight onto a floor and a wall.
TEST(PunctualPhotons, TheSunsShareOfEachTexelIsTheIntegralTheDirectionsLeaveOut) {
  PHYIR_SKIP_UNDER_SANITIZERS("PunctualPhotons.TakeNothingWhereNoneAreSent");
  expect_share_is_the_integral_left_out(skylight_room(), 65536, 4000,
                                        {{"on the wall facing the sun patch", {-1.99f, 1.2f, 0.4f}, {1, 0, 0}},
                                         {"30 cm above the floor beside the sun patch", {0.0f, 0.3f, -0.8f}, {0, 1, 0}},
                                         {"on the ceiling by the skylight", {-0.9f, 2.59f, 0.0f}, {0, -1, 0}}});
}

TEST(PunctualPhotons, TakeNothingWhereNoneAreSent) {
  scenes::Scene sunny = skylight_room();
  const RenderScene rs(sunny);
  uint64_t rays = 0;
  EXPECT_TRUE(PunctualPhotons(rs, 4096, 4, scenes::Bounds(), 1, &rays).empty())
      << "the sun sends none where no probe is";
  EXPECT_EQ(rays, 0u);
  const scenes::Scene bulb = bulb_room();
  const RenderScene with_bulb(bulb);
  EXPECT_TRUE(PunctualPhotons(with_bulb, 0, 4, bulb.bounds, 1, &rays).empty()) << "0 photons per light: off";
  const PunctualPhotons photons(with_bulb, 4096, 4, bulb.bounds, 1, &rays);
  EXPECT_FALSE(photons.empty());
  // Next to the bulb they land densely and take nearly all of its light; across the room
  // they take none, and never the spot's light where its cone does not reach.
  const float texel = equirect_texel_solid_angle(4, kW, kH);
  float shares[PunctualPhotons::kMaxLights];
  ASSERT_TRUE(photons.shares({0.0f, 0.01f, 0.0f}, {0.32f, 2.6f, 0.2f}, {0, -1, 0}, texel, shares));
  EXPECT_GT(shares[0], 0.9f);
  EXPECT_EQ(shares[1], 0.0f);
  EXPECT_FALSE(photons.shares({0.0f, 0.01f, 0.0f}, {1.9f, 2.6f, 1.4f}, {0, -1, 0}, texel, shares));
  // The sun's, kept to a box round the floor's sun patch: they take its light on the patch,
  // none on the wall outside the box, nor in the box where the ceiling shades the floor (the
  // beam's cells there reach no probe: their pilots land on the ceiling's back).
  scenes::Bounds round_patch;
  round_patch.extend({0.0f, 0.0f, -0.3f});
  round_patch.extend({1.9f, 0.05f, 1.4f});
  const PunctualPhotons sun(rs, 4096, 4, round_patch, 1, &rays);
  EXPECT_GT(sun.size(), 1000u);
  const glm::vec3 origin(-1.9f, 1.2f, 0.4f);
  EXPECT_TRUE(sun.shares(origin, {0.9f, 0.0f, 0.6f}, {0, 1, 0}, texel, shares));
  EXPECT_GT(shares[0], 0.5f);
  EXPECT_FALSE(sun.shares(origin, {2.0f, 1.0f, 0.6f}, {-1, 0, 0}, texel, shares)) << "outside the box";
  EXPECT_FALSE(sun.shares(origin, {0.1f, 0.0f, -0.2f}, {0, 1, 0}, texel, shares)) << "in the ceiling's shade";
}

// A floor probe's cache-mode settings, the lights' own texels left out (exact either way).
ProbeSettings cache_settings(int photons, uint64_t seed, float balance = 0.0f) {
  ProbeSettings s = settings_for(ProbeMode::kCache, 4, kH, kW, 3);
  s.seed = seed;
  s.cache.samples_per_cell = 128;
  s.punctual_lights = false;
  s.photons_per_light = photons;
  s.balance = balance;
  return s;
}

// The relative RMSE of the first probe's texels within `cone` radians of `towards` (the bulb's
// halo on the ceiling, from the floor): the rest of the probe is the same with and without
// photons.
double halo_rmse(const Image& a, const Image& reference, const glm::vec3& towards, float cone) {
  double se = 0.0, sum = 0.0;
  int n = 0;
  for (int r = 0; r < kH; ++r)
    for (int c = 0; c < kW; ++c) {
      if (glm::dot(probe_texel_direction(r, c, kH, kW, glm::vec2(0.5f)), towards) < std::cos(cone)) continue;
      ++n;
      for (int ch = 0; ch < 3; ++ch) {
        const double d = a.at(c, r, ch) - reference.at(c, r, ch);
        se += d * d, sum += std::abs(reference.at(c, r, ch));
      }
    }
  return std::sqrt(se / (3 * n)) / (sum / (3 * n));
}

double probe_mean(const Image& a) {
  double sum = 0.0;
  for (int r = 0; r < kH; ++r)
    for (int c = 0; c < kW; ++c) sum += luminance(glm::vec3(a.at(c, r, 0), a.at(c, r, 1), a.at(c, r, 2)));
  return sum / (kH * kW);
}

// Over three seeds, a probe rendered (by `render`, from its settings) with and without
// photons against the path mode's `reference`: the texels within `cone` of `towards` have at
// most `ratio` x the error with photons as without, and the probe's mean stays. `balance`:
// the probe's extra directions for its noisiest texels (docs/probes-estimator.md,
// "Balancing the texels' noise").
template <typename Render>
void expect_photons_help(const char* what, Render render, const Image& reference, const glm::vec3& towards,
                         float cone, float balance = 0.0f, double ratio = 0.8) {
  double with = 0.0, without = 0.0, mean_with = 0.0, mean_without = 0.0;
  const int seeds = 3;
  for (uint64_t seed = 10; seed < 10 + seeds; ++seed) {
    const Image a = render(cache_settings(4096, seed, balance));
    const Image b = render(cache_settings(0, seed, balance));
    with += halo_rmse(a, reference, towards, cone) / seeds, without += halo_rmse(b, reference, towards, cone) / seeds;
    mean_with += probe_mean(a), mean_without += probe_mean(b);
  }
  std::printf("%s against path mode, balance %.0f: relative RMSE %.4f with photons, %.4f without; probe means %.5f, %.5f\n",
              what, balance, with, without, mean_with / seeds, mean_without / seeds);
  EXPECT_LT(with, ratio * without) << what;
  EXPECT_NEAR(mean_with / mean_without, 1.0, 0.03) << what;
}

// A floor probe under the bulb: the texels that see the bright disc round it on the ceiling
// agree with the path mode better with photons, over seeds, and the probe's mean stays.
// Balanced, the halo's texels take hundreds of directions and the photons weigh against them
// (their count as spp / directions): about as good with photons as without (measured 0.059,
// 0.056; counted against spp alone, 0.164).
TEST(PunctualPhotons, AFloorProbeUnderABulbSeesItsHaloBetter) {
  PHYIR_SKIP_UNDER_SANITIZERS("PunctualPhotons.TakeNothingWhereNoneAreSent");
  const scenes::Scene scene = bulb_room();
  const glm::vec3 origin(-0.4f, 0.01f, 0.5f);
  const glm::vec3 towards = glm::normalize(scene.lights[0].position - origin);
  ProbeSettings path = cache_settings(0, 1);
  path.mode = ProbeMode::kPath;
  path.spp = 4096;
  const Image reference = render_single(scene, origin, path);
  auto render = [&](const ProbeSettings& s) { return render_single(scene, origin, s); };
  expect_photons_help("the halo's texels", render, reference, towards, 0.44f);
  expect_photons_help("the halo's texels", render, reference, towards, 0.44f, 1.0f, 1.15);
}

// A wall probe facing the skylight room's sun patch, rendered with two more probes in
// opposite corners of the room: the sun's photons go where a view's probes are (the box round
// them), and the rim of the patch is seen better with them. The patch's texels against path
// mode, over seeds; the probe's mean stays. Balanced, about as good with photons as without
// (over twelve seeds 0.078 against 0.091; three at a time, 0.70-0.98 of it).
TEST(PunctualPhotons, AWallProbeSeesTheSunPatchBetter) {
  PHYIR_SKIP_UNDER_SANITIZERS("PunctualPhotons.TakeNothingWhereNoneAreSent");
  const scenes::Scene scene = skylight_room();
  const RenderScene rs(scene);
  std::vector<ProbeSite> sites = single_site(glm::vec3(-1.99f, 1.2f, 0.4f));
  sites[0].surface = glm::vec3(-2.0f, 1.2f, 0.4f);
  sites[0].normal = glm::vec3(1.0f, 0.0f, 0.0f);
  for (const glm::vec3& corner : {glm::vec3(-1.9f, 0.01f, -1.4f), glm::vec3(1.9f, 2.59f, 1.4f)})
    sites.push_back(single_site(corner)[0]);
  const glm::vec3 patch_centre(0.91f, 0.0f, 0.65f);
  const glm::vec3 towards = glm::normalize(patch_centre - sites[0].origin);
  auto render = [&](ProbeSettings s) {
    s.layout.grid_width = 3;
    const ProbeOutput out = ProbeRenderer(rs, analyse_effects(scene, false), s).render_at(sites, {0});
    EXPECT_EQ(out.stats.counters.nonfinite_samples, 0u);
    if (s.mode == ProbeMode::kCache && s.photons_per_light > 0) {
      EXPECT_GT(out.stats.photons, 100u) << "the sun's photons land round the probes";
    }
    return out.mosaic;
  };
  ProbeSettings path = cache_settings(0, 1);
  path.mode = ProbeMode::kPath;
  path.spp = 4096;
  const Image reference = render(path);
  expect_photons_help("the sun patch's texels", render, reference, towards, 0.35f);
  expect_photons_help("the sun patch's texels", render, reference, towards, 0.35f, 1.0f, 1.15);
}

}  // namespace
}  // namespace phyir::render
