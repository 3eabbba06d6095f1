// The radiance cache's fill with light subpaths joined at its points (docs/light-subpaths.md):
// a floor point's indirect irradiance under a bulb 3 cm below the ceiling has the same
// mean with and without them, and far less variance with them (without, a few cosine rays
// that find the ceiling round the bulb carry most of the light).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "phyir/core/safe_math.h"
#include "phyir/render/effects.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "phyir/render/streams.h"
#include "radiance_cache.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

struct Estimate {
  double mean = 0.0, variance = 0.0, standard_error = 0.0;
};

Estimate fill_estimates(const RenderScene& rs, bool light_subpaths, int n) {
  PathSettings path;
  path.light_subpaths = light_subpaths;
  const RadianceCache cache(rs, analyse_effects(rs.scene(), false), path, RadianceCacheSettings{});
  CachePoint point;
  point.position = glm::vec3(-0.5f, 0.0f, -0.7f);
  point.shading_normal = point.geometric_normal = glm::vec3(0.0f, 1.0f, 0.0f);
  PathCounters counters;
  Rng rng(5, 1);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec2 u = rng.next_2d();
    const CachedIrradiance e = cache.estimate(point, u, false, 0.0f, glm::vec2(0.0f), sample_key(3, 0, uint64_t(i)), &counters);
    const double l = luminance(e.indirect);
    sum += l;
    sum2 += l * l;
  }
  EXPECT_EQ(counters.nonfinite_samples, 0u);
  Estimate r;
  r.mean = sum / n;
  r.variance = std::max(0.0, sum2 / n - r.mean * r.mean);
  r.standard_error = std::sqrt(r.variance / n);
  return r;
}

TEST(RadianceCacheSubpaths, TheFillKeepsItsMeanAndLosesMostOfItsVariance) {
  scenes::Scene scene = test::make_box_room(glm::vec3(-1.5f, 0.0f, -2.0f), glm::vec3(1.5f, 2.5f, 2.0f),
                                            test::make_material(glm::vec3(0.7f)));
  scene.lights.push_back(test::make_point_light(20.0f, glm::vec3(0.3f, 2.47f, 0.5f)));
  const RenderScene rs(scene);
  const Estimate without = fill_estimates(rs, false, 200000), with = fill_estimates(rs, true, 50000);
  std::printf("[ fill ] without %.5f +- %.5f, with %.5f +- %.5f, variance ratio %.1f\n", without.mean,
              without.standard_error, with.mean, with.standard_error, without.variance / with.variance);
  ASSERT_GT(with.mean, 0.0);
  EXPECT_LT(std::abs(with.mean - without.mean), 4.0 * std::hypot(without.standard_error, with.standard_error));
  EXPECT_GT(without.variance, 4.0 * with.variance);
}

}  // namespace
}  // namespace phyir::render
