// Which directions make a probe texel hard (docs/probes-estimator.md, "Hard texels"): a light
// seen directly, the environment included, as glass and glossy surfaces do; a diffuse hit or
// a black sky does not, and the sky apart from other hard hits (it takes more directions).
// And a probe under a sky seen between bars: every texel that sees the sky is supersampled,
// and the texels along the bars agree with path mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "phyir/core/image.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/effects.h"
#include "phyir/render/environment_light.h"
#include "phyir/render/probe_renderer.h"
#include "probe_texel_estimator.h"
#include "single_probe.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

std::unique_ptr<EnvironmentLight> uniform_sky(float radiance) {
  return std::make_unique<EnvironmentLight>(Image(16, 8, 3, radiance));
}

// A 2 x 2 m grey floor at y = 0, nothing else: a ray upwards escapes to the environment.
scenes::Scene floor_only() {
  scenes::Scene scene;
  const int m = test::add_material(scene, test::make_material(glm::vec3(0.5f)));
  test::add_quad(scene, glm::vec3(-1.0f, 0.0f, -1.0f), glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(2.0f, 0.0f, 0.0f), m,
                 "floor");
  return scene;
}

struct Sampled {
  glm::vec3 value{0.0f};
  uint8_t seen = 0;  // TexelEstimator::Seen
  bool hard() const { return seen & TexelEstimator::kSeenHard; }
  bool sky() const { return seen & TexelEstimator::kSeenSky; }
};

Sampled sample_once(const RenderScene& rs, const scenes::Scene& scene, bool environment, const Ray& ray,
                    TexelEstimator::Part part) {
  // No bounce: the first hit's emission alone, so no cache is needed.
  const ProbeSettings settings = settings_for(ProbeMode::kCache, 4, 16, 32, 0);
  const TexelEstimator estimator(rs, analyse_effects(scene, environment), settings, nullptr);
  Sampled s;
  TexelEstimator::SampleNotes notes;
  PathCounters counters;
  s.value = estimator.sample(ray, 7, part, FootCorrection(), 0.0f, &notes, &counters);
  s.seen = notes.seen;
  return s;
}

TEST(TexelEstimatorHard, TheSkySeenDirectlyMakesADirectionHardAsALightDoes) {
  const scenes::Scene scene = floor_only();
  const Ray up{glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
  const RenderScene sky(scene, uniform_sky(2.0f));
  const Sampled seen = sample_once(sky, scene, true, up, TexelEstimator::Part::kAll);
  EXPECT_TRUE(seen.hard());
  EXPECT_TRUE(seen.sky()) << "the sky's texels take more directions than other hard ones";
  EXPECT_FLOAT_EQ(seen.value.x, 2.0f);
  // Where the light seen first is estimated apart, the rest holds no sky and nothing hard.
  const Sampled rest = sample_once(sky, scene, true, up, TexelEstimator::Part::kRest);
  EXPECT_FALSE(rest.hard());
  EXPECT_EQ(rest.value, glm::vec3(0.0f));
  const RenderScene black(scene, uniform_sky(0.0f));
  EXPECT_FALSE(sample_once(black, scene, true, up, TexelEstimator::Part::kAll).hard());
  const RenderScene none(scene);
  EXPECT_FALSE(sample_once(none, scene, false, up, TexelEstimator::Part::kAll).hard());
}

TEST(TexelEstimatorHard, AnEmitterSeenIsHardButNotSky) {
  scenes::Scene scene = floor_only();
  scene.materials[0] = test::make_emitter(glm::vec3(5.0f));
  const RenderScene rs(scene, uniform_sky(2.0f));
  const Ray down{glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f)};
  const Sampled lamp = sample_once(rs, scene, true, down, TexelEstimator::Part::kAll);
  EXPECT_TRUE(lamp.hard());
  EXPECT_FALSE(lamp.sky());
  EXPECT_FLOAT_EQ(lamp.value.x, 5.0f);
}

TEST(TexelEstimatorHard, ADiffuseHitIsNotHard) {
  const scenes::Scene scene = floor_only();
  const RenderScene sky(scene, uniform_sky(2.0f));
  const Ray down{glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f)};
  EXPECT_FALSE(sample_once(sky, scene, true, down, TexelEstimator::Part::kAll).hard());
}

// A 2 x 2 x 1 m box without a lid under a uniform sky, three 4 cm bars across its opening.
scenes::Scene barred_box() {
  const glm::vec3 lo(-1.0f, 0.0f, -1.0f), hi(1.0f, 1.0f, 1.0f);
  scenes::Scene scene = test::make_box_room(lo, hi, test::make_material(glm::vec3(0.4f)));
  const auto ceiling = std::find_if(scene.meshes.begin(), scene.meshes.end(),
                                    [](const scenes::Mesh& m) { return m.name == "ceiling"; });
  EXPECT_NE(ceiling, scene.meshes.end()) << "make_box_room names its ceiling";
  if (ceiling != scene.meshes.end()) scene.meshes.erase(ceiling);
  for (float x : {-0.5f, 0.0f, 0.5f})
    test::add_box(scene, glm::vec3(x - 0.02f, hi.y - 0.04f, lo.z), glm::vec3(x + 0.02f, hi.y, hi.z), 0,
                  /*inward=*/false, "bar");
  return scene;
}

TEST(ProbeSky, EveryTexelThatSeesTheSkyIsSupersampledAndTheBarsMatchThePathMode) {
  const scenes::Scene scene = barred_box();
  const glm::vec3 origin(0.1f, 0.3f, 0.05f);
  const int h = 16, w = 32;
  const RenderScene rs(scene, uniform_sky(3.0f));
  const Effects effects = analyse_effects(scene, true);
  ProbeSettings path = settings_for(ProbeMode::kPath, 2048, h, w, 2);
  ProbeSettings cache = settings_for(ProbeMode::kCache, 4, h, w, 2);
  path.sharing.radius = cache.sharing.radius = 0;
  const ProbeOutput reference = ProbeRenderer(rs, effects, path).render_at(single_site(origin));
  const ProbeOutput out = ProbeRenderer(rs, effects, cache).render_at(single_site(origin));
  // The texels that see the sky: above the walls' rim, brighter than any wall can be.
  uint64_t sky_texels = 0;
  double squared = 0.0, sum = 0.0;
  int edge_texels = 0;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double ref = reference.mosaic.at(c, r, 0);
      if (!(ref > 1.0)) continue;
      ++sky_texels;
      if (ref > 2.9) continue;  // all sky
      ++edge_texels;
      const double e = out.mosaic.at(c, r, 0) - ref;
      squared += e * e, sum += ref;
    }
  ASSERT_GT(edge_texels, 4) << "the bars cross texels";
  EXPECT_GE(out.stats.supersampled_texels, sky_texels);
  const double relative = std::sqrt(squared / edge_texels) / (sum / edge_texels);
  std::printf("[ barred sky ] %llu sky texels, %d along bars or rims: relative RMSE %.4f; %llu supersampled\n",
              static_cast<unsigned long long>(sky_texels), edge_texels, relative,
              static_cast<unsigned long long>(out.stats.supersampled_texels));
  EXPECT_LT(relative, 0.04);
}

}  // namespace
}  // namespace phyir::render
