// The probes' radiance cache against exact answers: the direct irradiance it caches on a
// floor under a square light is Lambert's polygon formula at every point (which a
// cell-wide box filter would miss by several percent where the irradiance falls off;
// the interpolated lookup must not), cells near the light keep no direct light, and with
// one bounce there is no indirect light at all, smoothing the indirect light cuts its
// noise without moving its mean, the variances a lookup reports match its spread over
// seeds, and under the sky through a window (a floor under an
// environment black but for one bright texel, irradiance L x the texel's projected solid
// angle) the fill's own samples of the environment find it in every estimate, where cosine
// rays alone would in one of ~650.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "phyir/render/effects.h"
#include "phyir/render/environment_light.h"
#include "phyir/core/image.h"
#include "phyir/core/safe_math.h"
#include "radiance_cache.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

constexpr double kPi64 = 3.14159265358979323846;
constexpr float kLightHeight = 0.8f, kLightSide = 0.3f, kLe = 4.0f;
const glm::vec3 kLightCorner(-0.15f, kLightHeight, -0.15f);

// A large floor at y = 0 and a 0.3 m square light 0.8 m above it, facing down.
scenes::Scene floor_under_light() {
  scenes::Scene scene;
  const int floor_m = test::add_material(scene, test::make_material(glm::vec3(0.5f), 1.0f, 0.0f));
  const int light_m = test::add_material(scene, test::make_emitter(glm::vec3(kLe)));
  test::add_quad(scene, glm::vec3(-20, 0, 20), glm::vec3(40, 0, 0), glm::vec3(0, 0, -40), floor_m, "floor");
  test::add_quad(scene, kLightCorner, glm::vec3(kLightSide, 0, 0), glm::vec3(0, 0, kLightSide), light_m, "light");
  return scene;
}

double exact_irradiance(const glm::vec3& p) {
  std::vector<glm::dvec3> polygon;
  for (const glm::vec3& v : {kLightCorner, kLightCorner + glm::vec3(kLightSide, 0, 0),
                             kLightCorner + glm::vec3(kLightSide, 0, kLightSide), kLightCorner + glm::vec3(0, 0, kLightSide)})
    polygon.push_back(glm::dvec3(v - p));
  return test::polygon_irradiance(polygon, glm::dvec3(0, 1, 0), kLe);
}

CachePoint floor_point(float x, float z) {
  return CachePoint{glm::vec3(x, 0.0f, z), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)};
}

// Builds `cache` over the floor square [-half, half]^2, discovered from a 1 cm grid of points,
// and the `extra` points.
void build_over_floor(RadianceCache* cache, float half, const std::vector<CachePoint>& extra = {}) {
  RadianceCache::Collector collector;
  uint64_t priority = 0;
  for (float x = -half; x <= half; x += 0.01f)
    for (float z = -half; z <= half; z += 0.01f) collector.offer(*cache, floor_point(x, z), mix64(++priority));
  for (const CachePoint& p : extra) collector.offer(*cache, p, mix64(++priority));
  PathCounters counters;
  cache->build({&collector}, &counters);
}

struct BuiltCache {
  scenes::Scene scene = floor_under_light();
  RenderScene render_scene{scene};
  std::unique_ptr<RadianceCache> cache;
};

// A cache over the floor square [-half, half]^2, discovered from a 1 cm grid of points.
std::unique_ptr<BuiltCache> build_cache(float half, int max_bounces, int samples_per_cell,
                                        const std::vector<CachePoint>& extra = {}) {
  auto built = std::make_unique<BuiltCache>();
  RadianceCacheSettings settings;
  settings.samples_per_cell = samples_per_cell;
  settings.seed = 3;
  built->cache = std::make_unique<RadianceCache>(built->render_scene, analyse_effects(built->scene, false),
                                                 PathSettings{max_bounces, 3}, settings);
  build_over_floor(built->cache.get(), half, extra);
  return built;
}

// A cache over the floor square [-half, half]^2 (1 cm discovery grid), built and looked up
// at 400 random floor points: their irradiance (indirect part, red channel).
std::vector<double> floor_lookups(const RenderScene& render_scene, const scenes::Scene& scene, bool environment,
                                  int max_bounces, const RadianceCacheSettings& settings, float half) {
  RadianceCache cache(render_scene, analyse_effects(scene, environment), PathSettings{max_bounces, 3}, settings);
  build_over_floor(&cache, half);
  PathCounters counters;
  std::vector<double> out;
  Rng rng(5, 0);
  for (int n = 0; n < 400; ++n) {
    const glm::vec2 u = rng.next_2d();
    const CachePoint p = floor_point(-0.8f * half + 1.6f * half * u.x, -0.8f * half + 1.6f * half * u.y);
    out.push_back(double(cache.lookup(p, uint64_t(n), &counters).indirect.x));
  }
  return out;
}

double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / double(v.size());
}

double relative_rms_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(sum / double(a.size())) / (0.5 * (mean_of(a) + mean_of(b)));
}

TEST(RadianceCacheDirect, InterpolatedDirectIrradianceIsLambertsFormulaEverywhereOnTheFloor) {
  // One bounce: the cache holds the direct light only. The irradiance falls by ~10% across
  // a 5 cm cell half way out from under the light, so a box filter would be off by up to
  // ~5% at cells' edges; linear interpolation is second order (well under 1% here).
  const auto built = build_cache(0.6f, 1, 1024);
  const RadianceCache& cache = *built->cache;
  ASSERT_GT(cache.direct_cell_count(), 0u);
  Rng rng(17, 0);
  PathCounters counters;
  double worst = 0.0;
  for (int k = 0; k < 300; ++k) {
    const glm::vec2 u = rng.next_2d();
    const CachePoint p = floor_point(-0.5f + u.x, -0.5f + u.y);
    const CachedIrradiance e = cache.lookup(p, uint64_t(k), &counters);
    ASSERT_TRUE(e.has_direct) << "the floor is 0.8 m from the light: far enough to cache";
    EXPECT_EQ(e.indirect, glm::vec3(0.0f)) << "one bounce: no indirect light";
    const double exact = exact_irradiance(p.position);
    const double error = std::abs(e.direct.x - exact) / exact;
    worst = std::max(worst, error);
    EXPECT_LT(error, 0.02) << "at " << p.position.x << ", " << p.position.z << ": " << e.direct.x << " vs " << exact;
  }
  EXPECT_EQ(cache.fallbacks(), 0u);
  std::printf("[ cached direct irradiance ] largest relative error over 300 floor points: %.4f\n", worst);
}

TEST(RadianceCacheDirect, CellsNearALightKeepNoDirectLightAndZeroDisablesIt) {
  // A point 10 cm below the light (2 cell sizes; the threshold is 6) gets no direct light.
  const CachePoint near{glm::vec3(0.0f, kLightHeight - 0.1f, 0.0f), glm::vec3(0, -1, 0), glm::vec3(0, -1, 0)};
  const auto built = build_cache(0.2f, 2, 16, {near});
  PathCounters counters;
  EXPECT_FALSE(built->cache->lookup(near, 1, &counters).has_direct);
  EXPECT_TRUE(built->cache->lookup(floor_point(0.0f, 0.0f), 2, &counters).has_direct);

  auto off = std::make_unique<BuiltCache>();
  RadianceCacheSettings settings;
  settings.samples_per_cell = 16;
  settings.direct_distance_cells = 0.0f;
  RadianceCache cache(off->render_scene, analyse_effects(off->scene, false), PathSettings{2, 3}, settings);
  RadianceCache::Collector collector;
  collector.offer(cache, floor_point(0.0f, 0.0f), 1);
  cache.build({&collector}, &counters);
  EXPECT_EQ(cache.direct_cell_count(), 0u);
  EXPECT_FALSE(cache.lookup(floor_point(0.0f, 0.0f), 3, &counters).has_direct);
}

// A point light beside the square one: the cache keeps punctual light apart, exact at its
// cells' points (no sampling noise; a shadow edge is only blurred by the interpolation
// between cells), and its sampled direct light is the square light's alone. The square light
// casts the point light's hard shadow on the floor's far corner; points 10 cm or more from
// that shadow are checked.
TEST(RadianceCachePunctual, APointLightIsExactAtTheCellsAndLeftOutOfTheSampledDirectLight) {
  scenes::Scene scene = floor_under_light();
  scenes::PunctualLight point;
  point.type = scenes::PunctualLight::Type::Point;
  point.intensity = 2.0f * scenes::PunctualLight::kLumensPerWatt;  // 2 W/sr
  point.position = glm::vec3(0.4f, 1.2f, 0.4f);
  scene.lights = {point};
  const RenderScene render_scene(scene);
  RadianceCacheSettings settings;
  settings.samples_per_cell = 1024;
  settings.seed = 5;
  RadianceCache cache(render_scene, analyse_effects(scene, false), PathSettings{1, 3}, settings);
  build_over_floor(&cache, 0.6f);
  PathCounters counters;
  Rng rng(23, 0);
  double worst_punctual = 0.0, worst_direct = 0.0, sum_direct = 0.0, sum_exact_direct = 0.0;
  for (int k = 0; k < 300; ++k) {
    const glm::vec2 u = rng.next_2d();
    const CachePoint p = floor_point(-0.25f + 0.75f * u.x, -0.25f + 0.75f * u.y);
    const CachedIrradiance e = cache.lookup(p, uint64_t(k), &counters);
    ASSERT_TRUE(e.has_direct);
    const glm::vec3 d = point.position - p.position;
    const double exact_punctual = 2.0 * d.y / std::pow(double(glm::length(d)), 3.0);
    const double exact_direct = exact_irradiance(p.position);
    worst_punctual = std::max(worst_punctual, std::abs(e.punctual.x - exact_punctual) / exact_punctual);
    worst_direct = std::max(worst_direct, std::abs(e.direct.x - exact_direct) / exact_direct);
    EXPECT_NEAR(e.punctual.x, exact_punctual, 0.01 * exact_punctual) << "at " << p.position.x << ", " << p.position.z;
    sum_direct += e.direct.x, sum_exact_direct += exact_direct;
  }
  // The sampled part is the square light's alone (with the point light in it, it would be
  // three times as bright), within its fill noise: the samples that chose the point light
  // are dropped, so fewer are left than the cell's 1024.
  const double mean_error = sum_direct / sum_exact_direct - 1.0;
  std::printf("[ punctual kept apart ] largest relative error: punctual %.4f, sampled direct %.4f (mean %+.4f)\n",
              worst_punctual, worst_direct, mean_error);
  EXPECT_NEAR(mean_error, 0.0, 0.02);
  EXPECT_LT(worst_direct, 0.25);
}

// Smoothing the indirect light over a cell's neighbourhood: a floor lit only indirectly,
// by a wall a light shines on. Two caches of different seeds differ by far less with it
// than without, and the mean over the floor stays the same (the light changes slowly).
// A floor lit by a panel facing a wall: its indirect light is what the wall reflects.
scenes::Scene floor_beside_lit_wall() {
  scenes::Scene scene;
  const int white = test::add_material(scene, test::make_material(glm::vec3(0.8f), 1.0f, 0.0f));
  test::add_quad(scene, glm::vec3(-2, 0, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4), white, "floor");
  test::add_quad(scene, glm::vec3(0.6f, 0, 2), glm::vec3(0, 0, -4), glm::vec3(0, 2, 0), white, "wall");
  test::add_quad(scene, glm::vec3(-0.3f, 1.0f, -0.3f), glm::vec3(0, 0.4f, 0), glm::vec3(0, 0, 0.6f),
                 test::add_material(scene, test::make_emitter(glm::vec3(10.0f))), "light");
  return scene;
}

TEST(RadianceCacheFill, SmoothingTheIndirectLightCutsItsNoiseAndKeepsItsMean) {
  const scenes::Scene scene = floor_beside_lit_wall();
  const RenderScene render_scene(scene);
  auto lookups = [&](bool smooth, uint64_t seed) {
    RadianceCacheSettings settings;
    settings.samples_per_cell = 32;
    settings.smooth_indirect = smooth;
    settings.seed = seed;
    return floor_lookups(render_scene, scene, false, 2, settings, 0.5f);
  };
  auto rms_difference = [](const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
    return std::sqrt(sum / double(a.size()));
  };
  const auto raw1 = lookups(false, 1), raw2 = lookups(false, 2), smooth1 = lookups(true, 1), smooth2 = lookups(true, 2);
  const double raw_noise = rms_difference(raw1, raw2), smooth_noise = rms_difference(smooth1, smooth2);
  const double raw_mean = 0.5 * (mean_of(raw1) + mean_of(raw2)), smooth_mean = 0.5 * (mean_of(smooth1) + mean_of(smooth2));
  std::printf("[ smoothing ] indirect mean %.4f -> %.4f, seed-to-seed RMS %.4f -> %.4f\n", raw_mean, smooth_mean,
              raw_noise, smooth_noise);
  ASSERT_GT(raw_mean, 0.0);
  EXPECT_LT(smooth_noise, 0.6 * raw_noise);
  EXPECT_NEAR(smooth_mean / raw_mean, 1.0, 0.02);
}

// A closed grey room lit by a ceiling panel: light from every direction.
scenes::Scene grey_room() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-1.5f, 0.0f, -1.5f), glm::vec3(1.5f, 2.5f, 1.5f),
                                            test::make_material(glm::vec3(0.6f), 1.0f, 0.0f));
  test::add_quad(scene, glm::vec3(-0.3f, 2.49f, -0.3f), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0, 0.6f),
                 test::add_material(scene, test::make_emitter(glm::vec3(10.0f))), "light");
  return scene;
}

// Lookups at kPoints floor points of caches of kSeeds seeds, 128 estimates a cell (the default).
constexpr int kSeeds = 16, kPoints = 64;
std::vector<std::vector<CachedIrradiance>> lookups_over_seeds(const scenes::Scene& scene, bool smooth) {
  const RenderScene render_scene(scene);
  std::vector<std::vector<CachedIrradiance>> runs(kSeeds);
  for (int seed = 0; seed < kSeeds; ++seed) {
    RadianceCacheSettings settings;
    settings.samples_per_cell = 128;
    settings.smooth_indirect = smooth;
    settings.seed = uint64_t(seed + 1);
    RadianceCache cache(render_scene, analyse_effects(scene, false), PathSettings{2, 3}, settings);
    build_over_floor(&cache, 0.4f);
    Rng rng(5, 0);
    for (int n = 0; n < kPoints; ++n) {
      const glm::vec2 u = rng.next_2d();
      CachedIrradiance e;
      if (cache.interpolate(floor_point(-0.3f + 0.6f * u.x, -0.3f + 0.6f * u.y), &e)) runs[size_t(seed)].push_back(e);
    }
  }
  return runs;
}

// Summed over the points: the lookups' variance over seeds / the mean variance they report.
double measured_over_reported(const std::vector<std::vector<CachedIrradiance>>& runs, bool direct) {
  double measured = 0.0, reported = 0.0;
  for (int n = 0; n < kPoints; ++n) {
    double sum = 0.0, sum_squares = 0.0;
    for (const auto& run : runs) {
      const CachedIrradiance& e = run[size_t(n)];
      const double y = luminance(direct ? e.direct : e.indirect);
      sum += y, sum_squares += y * y;
      reported += direct ? e.direct_variance : e.indirect_variance;
    }
    measured += (sum_squares - sum * sum / kSeeds) / (kSeeds - 1);
  }
  return measured / (reported / kSeeds);
}

TEST(RadianceCacheFill, ReportedVariancesMatchTheLookupsSpreadOverSeeds) {
  // Unsmoothed cells are independent: the report should match but for its own noise and the
  // irradiance's variation over a cell, which it counts. Smoothed ones share most of their
  // cells, taken as one error, which overstates a lookup between cell centres by up to ~1.4x
  // (a box of 3 cells linearly interpolated keeps 10/36 of a cell's variance per axis, not 1/3).
  // The grey room has light all round; the floor beside a lit wall sees black over half its
  // hemisphere, the step between strata the fill's stratification removes.
  for (const auto& [name, scene] : {std::pair("grey room", grey_room()), std::pair("lit wall", floor_beside_lit_wall())}) {
    for (bool smooth : {false, true}) {
      const auto runs = lookups_over_seeds(scene, smooth);
      for (const auto& run : runs) {
        ASSERT_EQ(run.size(), size_t(kPoints));
        for (const CachedIrradiance& e : run) {
          ASSERT_TRUE(e.has_direct) << "the floor is over 30 cm (6 cells) from the light";
          EXPECT_GT(e.block, 0u);
        }
      }
      for (bool direct : {false, true}) {
        const double ratio = measured_over_reported(runs, direct);
        std::printf("[ fill variance ] %s, %s, %s: measured / reported %.3f\n", name, smooth ? "smoothed" : "unsmoothed",
                    direct ? "direct" : "indirect", ratio);
        EXPECT_GT(ratio, smooth && !direct ? 0.55 : 0.7);
        EXPECT_LT(ratio, smooth && !direct ? 1.2 : 1.4);
      }
    }
  }
}

// The grey room's ceiling meets its walls at a concave edge, where the (all indirect) light
// falls steeply in the last centimetres. A mean over a cell's 3 x 3 x 3 neighbours there has
// neighbours on the bright side only and reads 12% bright 1 cm from the wall, 4% at 3 cm;
// the smoothing's local linear fit follows the fall (within 3%). Reference: the cache's own
// estimator at 12 points along the wall, 2048 estimates each.
TEST(RadianceCacheFill, SmoothingFollowsTheFallOfLightTowardsAConcaveEdge) {
  const scenes::Scene scene = grey_room();
  const RenderScene render_scene(scene);
  RadianceCacheSettings settings;
  settings.samples_per_cell = 1024;
  settings.seed = 1;
  RadianceCache cache(render_scene, analyse_effects(scene, false), PathSettings{3, 3}, settings);
  const glm::vec3 down(0.0f, -1.0f, 0.0f);
  auto ceiling_point = [&](float x, float z) { return CachePoint{glm::vec3(x, 2.5f, z), down, down}; };
  RadianceCache::Collector collector;
  uint64_t priority = 0;
  for (float x = -1.49f; x <= 1.49f; x += 0.01f)
    for (float z = -1.49f; z <= 1.49f; z += 0.01f) collector.offer(cache, ceiling_point(x, z), mix64(++priority));
  PathCounters counters;
  cache.build({&collector}, &counters);
  for (float d : {0.01f, 0.03f, 0.06f, 0.12f}) {
    double cached = 0.0, reference = 0.0;
    constexpr int kAlong = 12, kEstimates = 2048;
    for (int n = 0; n < kAlong; ++n) {
      const CachePoint p = ceiling_point(-1.5f + d, -0.4f + 0.8f * float(n) / float(kAlong - 1));
      CachedIrradiance e;
      ASSERT_TRUE(cache.interpolate(p, &e));
      cached += luminance(e.indirect);
      for (int k = 0; k < kEstimates; ++k) {
        const glm::vec2 u((float(k % 64) + 0.5f) / 64.0f, (float(k / 64) + 0.5f) / 32.0f);
        reference += luminance(cache.estimate(p, u, false, 0.0f, glm::vec2(0.0f), mix64(uint64_t(n * kEstimates + k) + 77),
                                              &counters).indirect) / kEstimates;
      }
    }
    std::printf("[ concave edge ] %.0f cm from the wall: cached %.4f, reference %.4f (%+.1f%%)\n", 100.0 * d,
                cached / kAlong, reference / kAlong, 100.0 * (cached / reference - 1.0));
    EXPECT_NEAR(cached / reference, 1.0, 0.04) << d << " m from the wall";
  }
}

TEST(RadianceCacheEnvironment, ASmallBrightPatchOfSkyIsFoundByItsOwnSamples) {
  // 64 x 32 texels, black but for texel (column 5, row 8): theta from 45 to 50.6 degrees.
  constexpr int kWidth = 64, kHeight = 32, kRow = 8;
  constexpr float kL = 50.0f;
  Image sky(kWidth, kHeight, 3, 0.0f);
  for (int c = 0; c < 3; ++c) sky.at(5, kRow, c) = kL;
  scenes::Scene scene;
  test::add_quad(scene, glm::vec3(-20, 0, 20), glm::vec3(40, 0, 0), glm::vec3(0, 0, -40),
                 test::add_material(scene, test::make_material(glm::vec3(0.5f), 1.0f, 0.0f)), "floor");
  const RenderScene render_scene(scene, std::make_unique<EnvironmentLight>(sky));
  // Irradiance on an upward surface: L x (2 pi / W) x (sin^2 theta1 - sin^2 theta0) / 2.
  const double theta0 = double(kRow) * kPi64 / kHeight, theta1 = double(kRow + 1) * kPi64 / kHeight;
  const double exact = kL * (2.0 * kPi64 / kWidth) * 0.5 * (std::pow(std::sin(theta1), 2) - std::pow(std::sin(theta0), 2));
  RadianceCacheSettings settings;
  settings.samples_per_cell = 32;
  std::vector<std::vector<double>> runs;
  for (uint64_t seed : {1u, 2u}) {
    settings.seed = seed;
    runs.push_back(floor_lookups(render_scene, scene, true, 1, settings, 0.3f));
  }
  const double mean = 0.5 * (mean_of(runs[0]) + mean_of(runs[1]));
  const double seed_to_seed = relative_rms_difference(runs[0], runs[1]);
  std::printf("[ sky patch ] mean %.5f against exact %.5f (%+.4f), seed-to-seed relative RMS %.4f\n", mean, exact,
              mean / exact - 1.0, seed_to_seed);
  EXPECT_NEAR(mean / exact, 1.0, 0.02);
  // Cosine rays alone find the texel in 1 estimate of ~650: at 32 per cell (about 300 a
  // lookup after smoothing) the cells would differ by about their own value.
  EXPECT_LT(seed_to_seed, 0.05);
}

}  // namespace
}  // namespace phyir::render
