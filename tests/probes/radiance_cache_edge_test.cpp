// The radiance cache at a concave edge against an exact answer: a floor beside a black wall
// 10 cm high under a uniform sky of radiance 1, one bounce, so the floor's irradiance at a
// distance d from the wall is pi (1 - F), F = (1 - d / sqrt(d^2 + H^2)) / 2 the wall's view
// factor: it falls by a third within the last 5 cm, which 5 cm cells cannot follow alone.
// With the edge profiles the lookups follow it to the wall; without them they are far off.
// A convex edge (the top of a box) has no cells next to a concave edge.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "phyir/core/image.h"
#include "phyir/render/effects.h"
#include "phyir/render/environment_light.h"
#include "radiance_cache.h"
#include "phyir/render/render_scene.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/rng.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

constexpr float kWallHeight = 0.1f;

double exact_floor_irradiance(double d) {
  const double view_factor = 0.5 * (1.0 - d / std::sqrt(d * d + double(kWallHeight) * kWallHeight));
  return double(phyir::kPi) * (1.0 - view_factor);
}

std::unique_ptr<EnvironmentLight> white_sky() { return std::make_unique<EnvironmentLight>(Image(2, 1, 3, 1.0f)); }

// A floor (y = 0, facing up) and a black wall along x = 0 (facing +x), both 40 m long.
struct FloorBesideWall {
  scenes::Scene scene;
  std::unique_ptr<RenderScene> render_scene;
  std::unique_ptr<RadianceCache> cache;

  explicit FloorBesideWall(bool edge_profiles) {
    const int grey = test::add_material(scene, test::make_material(glm::vec3(0.5f), 1.0f, 0.0f));
    const int black = test::add_material(scene, test::make_material(glm::vec3(0.0f), 1.0f, 0.0f));
    test::add_quad(scene, glm::vec3(0, 0, 20), glm::vec3(20, 0, 0), glm::vec3(0, 0, -40), grey, "floor");
    test::add_quad(scene, glm::vec3(0, 0, 20), glm::vec3(0, 0, -40), glm::vec3(0, kWallHeight, 0), black, "wall");
    render_scene = std::make_unique<RenderScene>(scene, white_sky());
    RadianceCacheSettings settings;
    settings.edge_profiles = edge_profiles;
    settings.seed = 5;
    cache = std::make_unique<RadianceCache>(*render_scene, analyse_effects(scene, true), PathSettings{1, 3}, settings);
    RadianceCache::Collector collector;
    uint64_t priority = 0;
    const glm::vec3 up(0, 1, 0), east(1, 0, 0);
    for (float z = -0.3f; z <= 0.3f; z += 0.005f) {
      for (float x = 0.0005f; x <= 0.5f; x += 0.005f)
        collector.offer(*cache, CachePoint{glm::vec3(x, 0, z), up, up}, mix64(++priority));
      for (float y = 0.0005f; y <= kWallHeight; y += 0.005f)
        collector.offer(*cache, CachePoint{glm::vec3(0, y, z), east, east}, mix64(++priority));
    }
    PathCounters counters;
    cache->build({&collector}, &counters);
  }

  double lookup(float d) const {
    CachedIrradiance E;
    const glm::vec3 up(0, 1, 0);
    EXPECT_TRUE(cache->interpolate(CachePoint{glm::vec3(d, 0, 0.013f), up, up}, &E));
    return double(E.indirect.x);
  }
};

TEST(RadianceCacheEdge, TheFloorBesideAWallFollowsTheExactFallToTheWall) {
  const FloorBesideWall with(true), without(false);
  EXPECT_GT(with.cache->edge_cell_count(), 0u);
  EXPECT_GT(with.cache->edge_profile_count(), 0u);
  double worst_with = 0.0, worst_without = 0.0;
  for (float d : {0.0025f, 0.005f, 0.01f, 0.02f, 0.03f, 0.05f, 0.1f, 0.2f}) {
    const double exact = exact_floor_irradiance(d);
    const double e_with = with.lookup(d) / exact - 1.0, e_without = without.lookup(d) / exact - 1.0;
    std::printf("d = %5.2f cm: exact %.4f, with profiles %+.1f%%, without %+.1f%%\n", 100.0 * d, exact, 100.0 * e_with,
                100.0 * e_without);
    worst_with = std::max(worst_with, std::abs(e_with));
    worst_without = std::max(worst_without, std::abs(e_without));
  }
  EXPECT_LT(worst_with, 0.04);
  EXPECT_GT(worst_without, 0.15);  // what the profiles are for
}

TEST(RadianceCacheEdge, AConvexEdgeHasNoCellsNextToAConcaveEdge) {
  scenes::Scene scene;
  const int grey = test::add_material(scene, test::make_material(glm::vec3(0.5f), 1.0f, 0.0f));
  test::add_box(scene, glm::vec3(-0.5f, -1.0f, -0.5f), glm::vec3(0.5f, 0.0f, 0.5f), grey);
  RenderScene render_scene(scene, white_sky());
  RadianceCacheSettings settings;
  settings.samples_per_cell = 4;
  RadianceCache cache(render_scene, analyse_effects(scene, true), PathSettings{1, 3}, settings);
  RadianceCache::Collector collector;
  uint64_t priority = 0;
  const glm::vec3 up(0, 1, 0), east(1, 0, 0);
  for (float z = -0.2f; z <= 0.2f; z += 0.005f) {
    for (float x = 0.3f; x < 0.5f; x += 0.005f) collector.offer(cache, CachePoint{glm::vec3(x, 0, z), up, up}, mix64(++priority));
    for (float y = -0.2f; y < 0.0f; y += 0.005f)
      collector.offer(cache, CachePoint{glm::vec3(0.5f, y, z), east, east}, mix64(++priority));
  }
  PathCounters counters;
  cache.build({&collector}, &counters);
  EXPECT_GT(cache.cell_count(), 0u);
  EXPECT_EQ(cache.edge_cell_count(), 0u);
}

}  // namespace
}  // namespace phyir::render
