// The integrator against analytic answers: the white furnace (a convex object inside a
// uniformly emitting enclosure or environment returns exactly Le times the BRDF's directional
// albedo, computed here by quadrature), glass in the furnace, and direct lighting from a
// rectangular area light against brute-force quadrature over the light (itself checked
// against Lambert's closed-form polygon irradiance).
#include <gtest/gtest.h>

#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/frame.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/streams.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

// Mean and standard error of `n` path samples along `ray`.
struct Estimate {
  glm::dvec3 mean{0.0};
  double stderr_luminance = 0.0;
};

Estimate estimate(const PathTracer& tracer, const Ray& ray, int n, uint64_t seed) {
  glm::dvec3 sum(0.0);
  double sum_sq = 0.0, sum_l = 0.0;
  PathCounters counters;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 L = tracer.radiance(ray, sample_key(seed, 0, i), &counters);
    sum += glm::dvec3(L);
    const double l = luminance(L);
    sum_l += l;
    sum_sq += l * l;
  }
  EXPECT_EQ(counters.nonfinite_samples, 0u);
  Estimate e;
  e.mean = sum / double(n);
  const double mean_l = sum_l / n;
  e.stderr_luminance = std::sqrt(std::max(0.0, sum_sq / n - mean_l * mean_l) / n);
  return e;
}

// Directional albedo of the non-delta BRDF by midpoint quadrature over the hemisphere.
glm::dvec3 quadrature_albedo(const BrdfParams& p, const glm::vec3& wo) {
  const int nt = 1024, np = 1024;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < nt; ++i) {
    const double theta = (i + 0.5) * (kPi / 2) / nt;
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) * kTwoPi / np;
      const glm::vec3 wi(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      sum += glm::dvec3(brdf_eval(p, wo, wi)) * double(wi.z) * std::sin(theta);
    }
  }
  return sum * (double(kPi) / 2 / nt) * (double(kTwoPi) / np);
}

// A unit sphere at the origin, optionally inside a box that emits radiance 1 inward.
// Without the box the furnace is a constant environment of radiance 1.
scenes::Scene furnace_scene(const scenes::Material& sphere_material, bool enclosure) {
  scenes::Scene scene;
  if (enclosure) {
    const int emitter = test::add_material(scene, test::make_emitter(glm::vec3(1.0f)));
    test::add_box(scene, glm::vec3(-8.0f), glm::vec3(8.0f), emitter, /*inward=*/true, "furnace");
  }
  const int m = test::add_material(scene, sphere_material);
  test::add_uv_sphere(scene, glm::vec3(0.0f), 1.0f, m, 384, 192);
  return scene;
}

// A ray hitting the sphere at `normal` from a direction making cos = cos_view with it.
Ray ray_at_angle(const glm::vec3& normal, float cos_view) {
  const Frame frame(normal);
  const glm::vec3 wo = frame.to_world(glm::vec3(std::sqrt(1 - cos_view * cos_view), 0.0f, cos_view));
  Ray ray;
  ray.origin = normal + 3.0f * wo;
  ray.direction = -wo;
  return ray;
}

std::unique_ptr<EnvironmentLight> uniform_environment() {
  return std::make_unique<EnvironmentLight>(Image(16, 8, 3, 1.0f));
}

struct FurnaceCase {
  float base, roughness, metalness;
  bool enclosure;  // emissive triangles (next-event estimation) instead of the environment
};

class WhiteFurnace : public testing::TestWithParam<FurnaceCase> {};

TEST_P(WhiteFurnace, RadianceEqualsDirectionalAlbedo) {
  const FurnaceCase c = GetParam();
  const scenes::Scene scene =
      furnace_scene(test::make_material(glm::vec3(c.base), c.roughness, c.metalness), c.enclosure);
  const RenderScene rs(scene, c.enclosure ? nullptr : uniform_environment());
  // The enclosure reflects too (every material of the model does): one bounce counts only
  // the light that leaves the enclosure directly, which is the furnace's exact answer.
  PathSettings settings;
  if (c.enclosure) settings.max_bounces = 1;
  const PathTracer tracer(rs, analyse_effects(scene, !c.enclosure), settings);
  const glm::vec3 normal = glm::normalize(glm::vec3(0.3f, 0.8f, 0.52f));
  for (float cos_view : {1.0f, 0.7f, 0.4f}) {
    const Estimate e = estimate(tracer, ray_at_angle(normal, cos_view), 40000, 7);
    const BrdfParams p{glm::vec3(c.base), c.roughness, c.metalness};
    const glm::vec3 wo(std::sqrt(1 - cos_view * cos_view), 0.0f, cos_view);
    glm::dvec3 expected = quadrature_albedo(p, wo);
    if (is_mirror(c.roughness)) {
      // The mirror branch: F(n.v) G1(n.v)^2 with k = (R+1)^2/8 (brdf.h).
      const float k = (c.roughness + 1) * (c.roughness + 1) / 8;
      expected += glm::dvec3(F_SchlickSG(specular_F0(p.base_color, p.metalness), cos_view)) *
                  double(G1_SmithSchlick(cos_view, k) * G1_SmithSchlick(cos_view, k));
    }
    // 5 standard errors plus 1% for the tessellated sphere's normal variation.
    const double tolerance = 5 * e.stderr_luminance + 0.01 * luminance(glm::vec3(expected));
    EXPECT_NEAR(luminance(glm::vec3(e.mean)), luminance(glm::vec3(expected)), tolerance)
        << "R=" << c.roughness << " M=" << c.metalness << " B=" << c.base << " cos=" << cos_view;
  }
}

INSTANTIATE_TEST_SUITE_P(Materials, WhiteFurnace,
                         testing::Values(FurnaceCase{1.0f, 1.0f, 0.0f, false}, FurnaceCase{0.5f, 1.0f, 0.0f, true},
                                         FurnaceCase{1.0f, 0.5f, 0.0f, false}, FurnaceCase{1.0f, 0.3f, 1.0f, true},
                                         FurnaceCase{1.0f, 0.3f, 1.0f, false}, FurnaceCase{0.8f, 0.6f, 0.5f, true},
                                         FurnaceCase{1.0f, 0.0f, 1.0f, false}, FurnaceCase{0.5f, 0.0f, 0.0f, true}));

TEST(GlassFurnace, LosslessGlassSphereReturnsTheEnclosureRadiance) {
  scenes::Material glass = test::make_material(glm::vec3(1.0f), 0.0f, 0.0f, "glass");
  glass.transmission_factor = 1.0f;
  glass.ior = 1.5f;
  const scenes::Scene scene = furnace_scene(glass, false);
  const RenderScene rs(scene, uniform_environment());
  PathSettings settings;
  settings.max_bounces = 64;  // internal reflections
  const PathTracer tracer(rs, analyse_effects(scene, true), settings);
  ASSERT_TRUE(tracer.effects().transmission);
  for (float cos_view : {1.0f, 0.5f}) {
    const Estimate e = estimate(tracer, ray_at_angle(glm::vec3(0, 0, 1), cos_view), 4000, 3);
    EXPECT_NEAR(luminance(glm::vec3(e.mean)), 1.0, 5 * e.stderr_luminance + 0.01) << cos_view;
  }
}

// A glossy-ish floor point under a 1 m x 0.5 m light `height` metres up, facing down: the
// path tracer's value (next-event estimation + BRDF sampling, MIS) against quadrature. The
// floor is at y = `floor_y` (ray offsets scale with the coordinates' magnitude).
void check_plane_under_area_light(float height, float floor_y = 0.0f) {
  SCOPED_TRACE(testing::Message() << height << " m above a floor at y = " << floor_y);
  const glm::vec3 Le(5.0f);
  const BrdfParams floor_brdf{glm::vec3(0.6f), 0.4f, 0.0f};
  scenes::Scene scene;
  const int floor_m = test::add_material(scene, test::make_material(floor_brdf.base_color, floor_brdf.roughness, 0.0f));
  const int light_m = test::add_material(scene, test::make_emitter(Le));
  test::add_quad(scene, glm::vec3(-20, floor_y, 20), glm::vec3(40, 0, 0), glm::vec3(0, 0, -40), floor_m, "floor");
  // Edges chosen so cross(edge_u, edge_v) = -Y.
  const glm::vec3 corner(-0.3f, floor_y + height, -0.2f), eu(1.0f, 0, 0), ev(0, 0, 0.5f);
  test::add_quad(scene, corner, eu, ev, light_m, "light");
  const RenderScene rs(scene);
  const PathTracer tracer(rs, analyse_effects(scene, false), PathSettings{});

  const glm::vec3 shading_point(0.4f, floor_y, 0.3f);
  const glm::vec3 wo_world = glm::normalize(glm::vec3(-1.0f, 1.2f, 0.5f));
  Ray ray;
  ray.origin = shading_point + 2.0f * wo_world;
  ray.direction = -wo_world;

  // Brute-force quadrature over the light's area of f_r L cos cos' / r^2.
  const int n = 600;
  const Frame frame(glm::vec3(0, 1, 0));
  const glm::vec3 wo = frame.to_local(wo_world);
  glm::dvec3 expected(0.0);
  double cos_only = 0.0;
  const double dA = double(glm::length(eu)) * glm::length(ev) / (double(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec3 q = corner + eu * ((i + 0.5f) / n) + ev * ((j + 0.5f) / n);
      const glm::vec3 d = q - shading_point;
      const float r2 = glm::dot(d, d);
      const glm::vec3 wi_world = d / std::sqrt(r2);
      const double geometry = double(wi_world.y) * double(wi_world.y) / r2 * dA;  // cos at floor = cos at light here
      expected += glm::dvec3(brdf_eval(floor_brdf, wo, frame.to_local(wi_world)) * Le) * geometry;
      cos_only += geometry;
    }
  // The quadrature itself against the closed form.
  std::vector<glm::dvec3> poly;
  for (const glm::vec3& v : {corner, corner + eu, corner + eu + ev, corner + ev}) poly.push_back(glm::dvec3(v - shading_point));
  EXPECT_NEAR(cos_only * Le.x, test::polygon_irradiance(poly, glm::dvec3(0, 1, 0), Le.x), 1e-3 * cos_only * Le.x);

  const Estimate e = estimate(tracer, ray, 20000, 11);
  EXPECT_NEAR(e.mean.x, expected.x, 5 * e.stderr_luminance + 0.005 * expected.x);
  std::cout << "light " << height << " m up: path tracer " << e.mean.x << " +- " << e.stderr_luminance
            << ", quadrature " << expected.x << "\n";
}

TEST(DirectLighting, DiffusePlaneUnderAreaLightMatchesQuadrature) { check_plane_under_area_light(2.0f); }

// 20 cm under the light, where next-event estimation's samples reach the light at up to
// 70 degrees off its normal (the distance at which the probes' cache samples light per direction).
TEST(DirectLighting, DiffusePlaneCloseUnderAreaLightMatchesQuadrature) { check_plane_under_area_light(0.2f); }

// The same at the height of a room's furniture (a pillar top at 2.4 m), where a spawn
// offset is 61 um rather than 15 um at y = 0: shadow rays that offset only their origin
// all ended on the light itself there, and the estimate lost its next-event part.
TEST(DirectLighting, PlaneCloseUnderAreaLightAwayFromTheOriginMatchesQuadrature) {
  check_plane_under_area_light(0.2f, 2.4f);
}

// continue_from(hit) is radiance(ray) without the hit's emission and without tracing the
// ray again: the same streams from the hit on, so the same path, one ray fewer. In a room
// with glass, a mirror and an emitting ceiling (hits on the light itself included).
TEST(PathTracer, ContinuingFromAHitIsTheSamePathWithoutItsFirstRay) {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2, 0, -2), glm::vec3(2, 3, 2), test::make_material(glm::vec3(0.6f), 0.5f));
  scene.meshes[3].material = test::add_material(scene, test::make_emitter(glm::vec3(2.0f)));  // the ceiling
  scenes::Material glass = test::make_material(glm::vec3(1.0f), 0.0f);
  glass.transmission_factor = 1.0f;
  test::add_uv_sphere(scene, glm::vec3(0.5f, 1.0f, 0.0f), 0.4f, test::add_material(scene, glass), 24, 12);
  test::add_uv_sphere(scene, glm::vec3(-0.8f, 0.6f, 0.5f), 0.4f,
                      test::add_material(scene, test::make_material(glm::vec3(0.9f), 0.0f, 1.0f)), 24, 12);
  const RenderScene rs(scene);
  const PathTracer tracer(rs, analyse_effects(scene, false), PathSettings{});
  Rng rng(5, 1);
  int emitting = 0, transmitting = 0;
  constexpr int kBudgets[3] = {0, 1, 8};
  auto tracer_of = [&](int bounces) {  // radiance() with the same budget
    PathSettings settings;
    settings.max_bounces = bounces;
    return PathTracer(rs, analyse_effects(scene, false), settings);
  };
  const PathTracer whole_paths[3] = {tracer_of(kBudgets[0]), tracer_of(kBudgets[1]), tracer_of(kBudgets[2])};
  for (int i = 0; i < 4000; ++i) {
    const Ray ray{glm::vec3(0.0f, 1.5f, 1.5f), sample_uniform_sphere(rng.next_2d())};
    SurfaceInteraction si;
    ASSERT_TRUE(rs.trace(ray, &si));
    emitting += si.emits;
    transmitting += si.transmission > 0.0f;
    const uint64_t key = sample_key(9, uint64_t(i), 0);
    for (int n = 0; n < 3; ++n) {
      const int bounces = kBudgets[n];
      PathCounters whole, continued;
      const glm::vec3 a = whole_paths[n].radiance(ray, key, &whole);
      const glm::vec3 b = tracer.continue_from(si, ray, key, bounces, &continued) + (si.emits ? si.emission : glm::vec3(0.0f));
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-5f * std::max(a[c], 1.0f)) << i << " " << bounces;
      ASSERT_EQ(whole.rays, continued.rays + 1);
    }
  }
  EXPECT_GT(emitting, 100);
  EXPECT_GT(transmitting, 40);
}

TEST(Effects, SceneAnalysisFindsOnlyWhatIsThere) {
  scenes::Scene scene = test::make_box_room(glm::vec3(-1), glm::vec3(1));
  Effects e = analyse_effects(scene, false);
  EXPECT_FALSE(e.emitters);
  EXPECT_FALSE(e.transmission);
  EXPECT_FALSE(e.textures);
  EXPECT_FALSE(e.environment);
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(1)));
  test::add_quad(scene, glm::vec3(0, 0.9f, 0), glm::vec3(0.1f, 0, 0), glm::vec3(0, 0, 0.1f), light);
  scenes::Material glass = test::make_material();
  glass.transmission_factor = 1;
  const int g = test::add_material(scene, glass);
  test::add_uv_sphere(scene, glm::vec3(0), 0.2f, g, 8, 4);
  e = analyse_effects(scene, true);
  EXPECT_TRUE(e.emitters);
  EXPECT_TRUE(e.transmission);
  EXPECT_TRUE(e.environment);
}

TEST(Effects, UnusedMaterialsDoNotTurnEffectsOn) {
  scenes::Scene scene = test::make_box_room(glm::vec3(-1), glm::vec3(1));
  test::add_material(scene, test::make_emitter(glm::vec3(1)));  // no mesh uses it
  EXPECT_FALSE(analyse_effects(scene, false).emitters);
}

}  // namespace
}  // namespace phyir::render
