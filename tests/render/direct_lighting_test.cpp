// The light-transport layer every estimator calls (render/src/direct_lighting.cpp), against
// Lambert's formula for the irradiance of a floor point under a rectangular light:
//   kCosine  next-event estimation alone gives the irradiance;
//   MIS      with the power heuristic, light samples plus cosine rays weighted by
//            emitter_hit_weight() give it too (the two weights sum to one per direction);
//   multi    `light_samples` counts in both weights: n light samples against one ray;
//   weak     the shadow-ray roulette leaves the mean unchanged;
//   shadows  an occluder takes the light away, and the shadow ray is counted;
//   punctual punctual_light() gives a point light's f E cos exactly (one shadow ray per light
//            in front), and light samples with `punctual = false` the triangles' light alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"
#include "monte_carlo.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

constexpr float kRadiance = 3.0f;
const glm::vec3 kPoint(0.3f, 0.0f, 0.2f);  // on the floor, under the light's corner region
const glm::vec3 kCorner(-0.5f, 1.5f, -0.5f), kEdgeU(1.0f, 0.0f, 0.0f), kEdgeV(0.0f, 0.0f, 1.0f);  // faces -Y

scenes::Scene lit_floor(bool occluded) {
  scenes::Scene scene;
  const int grey = test::add_material(scene, test::make_material(glm::vec3(0.5f)));
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(kRadiance)));
  test::add_quad(scene, glm::vec3(-5, 0, 5), glm::vec3(10, 0, 0), glm::vec3(0, 0, -10), grey, "floor");
  test::add_quad(scene, kCorner, kEdgeU, kEdgeV, light, "light");
  if (occluded) test::add_quad(scene, glm::vec3(-2, 0.5f, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4), grey, "slab");
  return scene;
}

double lambert_irradiance() {
  std::vector<glm::dvec3> polygon;
  for (const glm::vec3& v : {kCorner, kCorner + kEdgeU, kCorner + kEdgeU + kEdgeV, kCorner + kEdgeV})
    polygon.push_back(glm::dvec3(v - kPoint));
  return test::polygon_irradiance(polygon, glm::dvec3(0, 1, 0), kRadiance);
}

ShadingPoint floor_point() {
  ShadingPoint x;
  x.position = kPoint;
  x.geometric_normal = glm::vec3(0, 1, 0);
  x.frame = Frame(x.geometric_normal);
  return x;
}

// The mean of `n` values of `sample(rng)`, with its standard error.
template <typename Sample>
test::MeanAndError mean_of(int n, uint64_t seed, Sample sample) {
  Rng rng(seed, 3);
  return test::monte_carlo(n, [&](int) { return sample(rng); });
}

// One light sample through the cosine lobe (irradiance), with the given options.
double light_sample(const RenderScene& rs, const DirectLightOptions& options, Rng& rng, PathCounters* c) {
  LightVariates u;
  u.select = rng.next_float();
  u.point = rng.next_2d();
  return sample_emitter_light(rs, floor_point(), u, options, glm::vec3(1.0f), &rng, c).x;
}

// One cosine-distributed ray's irradiance estimate: pi L w where it reaches the light (w = 1
// when not `weighted`).
double cosine_ray(const RenderScene& rs, int light_samples, Rng& rng, bool weighted = true, bool punctual = true) {
  const ShadingPoint x = floor_point();
  const glm::vec3 local = sample_cosine_hemisphere(rng.next_2d());
  const Ray ray{x.position + 1e-4f * x.geometric_normal, x.frame.to_world(local)};
  SurfaceInteraction si;
  if (!rs.trace(ray, &si) || !si.emits) return 0.0;
  const float w = weighted ? emitter_hit_weight(rs, x.position, local.z * kInvPi, si, light_samples, punctual) : 1.0f;
  return kPi * si.emission.x * w;
}

DirectLightOptions irradiance_options(bool mis, int light_samples = 1) {
  DirectLightOptions o;
  o.lobes = Lobes::kCosine;
  o.mis = mis;
  o.light_samples = light_samples;
  return o;
}

TEST(DirectLighting, LightSamplesAloneGiveLambertsIrradiance) {
  const scenes::Scene scene = lit_floor(false);
  const RenderScene rs(scene);
  PathCounters c;
  const test::MeanAndError m = mean_of(40000, 1, [&](Rng& rng) { return light_sample(rs, irradiance_options(false), rng, &c); });
  const double expected = lambert_irradiance();
  EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + 1e-3 * expected);
  EXPECT_EQ(c.rays, 40000u);  // one shadow ray per sample: the point sees the whole light
}

TEST(DirectLighting, MisWeightsOfLightSamplesAndCosineRaysSumToOne) {
  const scenes::Scene scene = lit_floor(false);
  const RenderScene rs(scene);
  const double expected = lambert_irradiance();
  for (int light_samples : {1, 4}) {
    PathCounters c;
    // `light_samples` light samples and one cosine ray per estimate.
    const test::MeanAndError m = mean_of(40000, 2 + uint64_t(light_samples), [&](Rng& rng) {
      double sum = 0.0;
      for (int k = 0; k < light_samples; ++k) sum += light_sample(rs, irradiance_options(true, light_samples), rng, &c);
      return sum / light_samples + cosine_ray(rs, light_samples, rng);
    });
    EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + 1e-3 * expected) << light_samples << " light samples";
  }
  // Unweighted, both strategies count the light: the test tells the weights from none.
  const test::MeanAndError both = mean_of(20000, 9, [&](Rng& rng) {
    PathCounters c;
    return light_sample(rs, irradiance_options(false), rng, &c) + cosine_ray(rs, 1, rng, false);
  });
  EXPECT_GT(both.mean, 1.8 * expected);
}

// Beside a bright bulb (a point light most light samples would choose), light samples that
// never choose it and cosine rays weighted against those samples give the panel's
// irradiance; weighted against samples that may choose it, the rays' share is too large.
TEST(DirectLighting, MisOfTheTrianglesAloneSumsToOneBesideAPunctualLight) {
  scenes::Scene scene = lit_floor(false);
  scene.lights = {test::make_point_light(50.0f, kPoint + glm::vec3(0.2f, 0.3f, 0.0f))};
  const RenderScene rs(scene);
  const double expected = lambert_irradiance();
  DirectLightOptions triangles = irradiance_options(true, 4);
  triangles.punctual = false;
  for (const bool matched : {true, false}) {
    PathCounters c;
    const test::MeanAndError m = mean_of(40000, 11, [&](Rng& rng) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k) sum += light_sample(rs, triangles, rng, &c);
      return sum / 4 + cosine_ray(rs, 4, rng, true, !matched);
    });
    if (matched) EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + 1e-3 * expected);
    else EXPECT_GT(m.mean, expected + 6.0 * m.standard_error) << "the test tells the matched weight from the other";
  }
}

TEST(DirectLighting, WeakShadowRayRouletteKeepsTheMean) {
  const scenes::Scene scene = lit_floor(false);
  const RenderScene rs(scene);
  DirectLightOptions rouletted = irradiance_options(false);
  rouletted.weak = float(4.0 * lambert_irradiance());  // every sample is "weak": most skip their ray
  PathCounters c;
  const test::MeanAndError m = mean_of(40000, 5, [&](Rng& rng) { return light_sample(rs, rouletted, rng, &c); });
  const double expected = lambert_irradiance();
  EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + 1e-3 * expected);
  EXPECT_LT(c.rays, 40000u / 2);
}

TEST(DirectLighting, AnOccluderTakesTheLightAway) {
  const scenes::Scene scene = lit_floor(true);
  const RenderScene rs(scene);
  PathCounters c;
  const test::MeanAndError m = mean_of(1000, 6, [&](Rng& rng) { return light_sample(rs, irradiance_options(false), rng, &c); });
  EXPECT_EQ(m.mean, 0.0);
  EXPECT_EQ(c.rays, 1000u);
}

// A point light over the floor beside the panel, coloured, and a sun under the floor (which
// can never light it): the expected irradiance from the light's definition, I / d^2 cos.
TEST(DirectLighting, PunctualLightsAreExactAndLeftOutOfTheSampledTrianglesOnRequest) {
  for (const bool occluded : {false, true}) {
    scenes::Scene scene = lit_floor(occluded);
    // Above the slab of lit_floor(true).
    const scenes::PunctualLight point = test::make_point_light(2.0f, glm::vec3(1.1f, 0.8f, -0.4f), {1.0f, 0.5f, 0.25f});
    scenes::PunctualLight sun;
    sun.type = scenes::PunctualLight::Type::Directional;
    sun.intensity = 5.0f * scenes::PunctualLight::kLumensPerWatt;
    sun.direction = glm::vec3(0.0f, 1.0f, 0.0f);  // shining upwards
    scene.lights = {point, sun};
    const RenderScene rs(scene);
    ShadingPoint x = floor_point();
    x.wo = glm::normalize(glm::vec3(0.3f, 0.2f, 0.9f));
    x.brdf = BrdfParams{glm::vec3(0.6f), 0.4f, 0.3f};
    const glm::vec3 d = point.position - kPoint;
    const glm::vec3 wi = x.frame.to_local(glm::normalize(d));
    const glm::vec3 E = occluded ? glm::vec3(0.0f) : point.color * 2.0f * wi.z / glm::dot(d, d);
    PathCounters c;
    const glm::vec3 irradiance = punctual_light(rs, x, Lobes::kCosine, &c);
    const glm::vec3 reflected = punctual_light(rs, x, Lobes::kAll, &c);
    const glm::vec3 f = brdf_eval(x.brdf, x.wo, wi);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(irradiance[ch], E[ch], 1e-5f * E.x) << "occluded " << occluded;
      EXPECT_NEAR(reflected[ch], f[ch] * E[ch], 1e-5f * E.x) << "occluded " << occluded;
    }
    EXPECT_EQ(c.rays, 2u) << "one shadow ray per call for the point light, none for the sun below";
    if (occluded) continue;
    // Light samples: the panel and the point light, or the panel alone with punctual = false.
    DirectLightOptions both = irradiance_options(false), triangles = both;
    triangles.punctual = false;
    const test::MeanAndError all = mean_of(40000, 7, [&](Rng& rng) { return light_sample(rs, both, rng, &c); });
    const test::MeanAndError panel = mean_of(40000, 7, [&](Rng& rng) { return light_sample(rs, triangles, rng, &c); });
    EXPECT_NEAR(all.mean, lambert_irradiance() + E.x, 4.0 * all.standard_error + 1e-3 * E.x);
    EXPECT_NEAR(panel.mean, lambert_irradiance(), 4.0 * panel.standard_error + 1e-3 * lambert_irradiance());
  }
}

}  // namespace
}  // namespace phyir::render
