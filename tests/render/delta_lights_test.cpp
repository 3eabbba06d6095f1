// Punctual lights (delta_lights.h) through the light-transport layer, against analytic
// irradiance: a point light gives I cos / d^2, a spot the same times the extension's cone
// ramp, a directional light E cos exactly where an opening lets it through and nothing
// behind closed walls. Chosen together with emissive triangles (spatially or by power), the
// estimate stays unbiased and MIS with cosine rays still sums to one. Degenerate lights give
// zeros, never NaN or Inf, and the path tracer runs next-event estimation for them alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/effects.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"
#include "monte_carlo.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

using Type = scenes::PunctualLight::Type;

scenes::PunctualLight make_light(Type type, float watts, const glm::vec3& position,
                                 const glm::vec3& direction = glm::vec3(0, -1, 0)) {
  scenes::PunctualLight light;
  light.type = type;
  light.intensity = watts * scenes::PunctualLight::kLumensPerWatt;  // cd or lx
  light.position = position;
  light.direction = glm::normalize(direction);
  return light;
}

// A grey floor (y = 0, facing +Y) with the given lights.
scenes::Scene floor_with(const std::vector<scenes::PunctualLight>& lights) {
  scenes::Scene scene;
  const int grey = test::add_material(scene, test::make_material(glm::vec3(0.5f)));
  test::add_quad(scene, glm::vec3(-5, 0, 5), glm::vec3(10, 0, 0), glm::vec3(0, 0, -10), grey, "floor");
  scene.lights = lights;
  return scene;
}

ShadingPoint floor_point(const glm::vec3& p) {
  ShadingPoint x;
  x.position = p;
  x.geometric_normal = glm::vec3(0, 1, 0);
  x.frame = Frame(x.geometric_normal);
  return x;
}

DirectLightOptions irradiance_options(bool mis = false) {
  DirectLightOptions o;
  o.lobes = Lobes::kCosine;  // f = 1: the estimate is the irradiance
  o.mis = mis;
  return o;
}

// One next-event estimate of the irradiance at floor point p.
double irradiance_sample(const RenderScene& rs, const glm::vec3& p, float u_select, const glm::vec2& u_point,
                         bool mis = false, PathCounters* counters = nullptr) {
  PathCounters local;
  return sample_emitter_light(rs, floor_point(p), LightVariates{u_select, u_point}, irradiance_options(mis),
                              glm::vec3(1.0f), nullptr, counters ? counters : &local)
      .y;
}

double point_irradiance(double intensity, const glm::vec3& light, const glm::vec3& p) {
  const glm::dvec3 d = glm::dvec3(light) - glm::dvec3(p);
  const double dist2 = glm::dot(d, d);
  return intensity * (d.y / std::sqrt(dist2)) / dist2;
}

TEST(DeltaLights, PointLightGivesIntensityTimesCosineOverDistanceSquared) {
  const glm::vec3 lamp(0.3f, 2.0f, -0.4f);
  const RenderScene rs(floor_with({make_light(Type::Point, 3.0f, lamp)}));
  PathCounters counters;
  for (const glm::vec3 p : {glm::vec3(0.3f, 0, -0.4f), glm::vec3(1, 0, 0), glm::vec3(-2, 0, 3), glm::vec3(4, 0, 4)}) {
    const double expected = point_irradiance(3.0, lamp, p);
    EXPECT_NEAR(irradiance_sample(rs, p, 0.5f, glm::vec2(0.5f), false, &counters), expected, 1e-5 * expected) << p.x;
  }
  EXPECT_EQ(counters.rays, 4u);  // one shadow ray each
}

TEST(DeltaLights, SpotLightFollowsItsConeRamp) {
  scenes::PunctualLight spot = make_light(Type::Spot, 5.0f, glm::vec3(0, 2, 0));
  spot.inner_cone_angle = 0.3f;
  spot.outer_cone_angle = 0.5f;
  const RenderScene rs(floor_with({spot}));
  for (float angle : {0.0f, 0.2f, 0.3f, 0.35f, 0.4f, 0.45f, 0.5f, 0.6f, 1.2f}) {
    const glm::vec3 p(2.0f * std::tan(angle), 0.0f, 0.0f);
    const double cos_outer = std::cos(0.5), ramp = (std::cos(double(angle)) - cos_outer) / (std::cos(0.3) - cos_outer);
    const double falloff = angle <= 0.3f ? 1.0 : angle >= 0.5f ? 0.0 : ramp * ramp;
    const double expected = point_irradiance(5.0, spot.position, p) * falloff;
    EXPECT_NEAR(irradiance_sample(rs, p, 0.5f, glm::vec2(0.5f)), expected, 1e-4 * expected + 1e-9) << angle;
  }
}

// A closed room [-2, 2] x [0, 3] x [-2, 2] whose ceiling has the square opening |x|, |z| < 0.5
// (or none), lit by a sun going along `sun`.
scenes::Scene room_with_opening(bool opening, const glm::vec3& sun) {
  scenes::Scene scene;
  const int grey = test::add_material(scene, test::make_material(glm::vec3(0.5f)));
  test::add_quad(scene, glm::vec3(-2, 0, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4), grey, "floor");
  test::add_quad(scene, glm::vec3(-2, 0, -2), glm::vec3(4, 0, 0), glm::vec3(0, 3, 0), grey, "wall -z");
  test::add_quad(scene, glm::vec3(2, 0, 2), glm::vec3(-4, 0, 0), glm::vec3(0, 3, 0), grey, "wall +z");
  test::add_quad(scene, glm::vec3(-2, 0, 2), glm::vec3(0, 0, -4), glm::vec3(0, 3, 0), grey, "wall -x");
  test::add_quad(scene, glm::vec3(2, 0, -2), glm::vec3(0, 0, 4), glm::vec3(0, 3, 0), grey, "wall +x");
  // Ceiling (facing down) as four strips around the opening, or whole.
  auto ceiling = [&](float x0, float x1, float z0, float z1) {
    test::add_quad(scene, glm::vec3(x0, 3, z0), glm::vec3(x1 - x0, 0, 0), glm::vec3(0, 0, z1 - z0), grey, "ceiling");
  };
  if (opening) {
    ceiling(-2, 2, -2, -0.5f);
    ceiling(-2, 2, 0.5f, 2);
    ceiling(-2, -0.5f, -0.5f, 0.5f);
    ceiling(0.5f, 2, -0.5f, 0.5f);
  } else {
    ceiling(-2, 2, -2, 2);
  }
  scene.lights = {make_light(Type::Directional, 7.0f, glm::vec3(0.0f), sun)};
  return scene;
}

TEST(DeltaLights, DirectionalLightLightsExactlyTheOpeningsProjection) {
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  const RenderScene rs(room_with_opening(true, sun));
  // A floor point is lit when the ray towards the sun crosses y = 3 inside the opening.
  const glm::vec2 shift = 3.0f * glm::vec2(sun.x, sun.z) / sun.y;  // floor -> ceiling, in x and z
  int lit = 0, dark = 0;
  for (float x = -1.95f; x < 2.0f; x += 0.1f) {
    for (float z = -1.95f; z < 2.0f; z += 0.1f) {
      const glm::vec2 at_ceiling = glm::vec2(x, z) + shift;
      const float margin = 0.5f - std::max(std::abs(at_ceiling.x), std::abs(at_ceiling.y));
      if (std::abs(margin) < 0.01f) continue;  // on the shadow's edge
      const double expected = margin > 0.0f ? 7.0 * -sun.y : 0.0;
      EXPECT_NEAR(irradiance_sample(rs, glm::vec3(x, 0, z), 0.5f, glm::vec2(0.5f)), expected, 1e-5) << x << " " << z;
      (margin > 0.0f ? lit : dark)++;
    }
  }
  EXPECT_GT(lit, 50);  // the 1 m^2 patch, at 0.1 m spacing
  EXPECT_GT(dark, 1000);
}

TEST(DeltaLights, DirectionalLightBehindClosedWallsContributesNothing) {
  const RenderScene rs(room_with_opening(false, glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f))));
  for (float x = -1.9f; x < 2.0f; x += 0.2f)
    for (float z = -1.9f; z < 2.0f; z += 0.2f) EXPECT_EQ(irradiance_sample(rs, glm::vec3(x, 0, z), 0.5f, glm::vec2(0.5f)), 0.0);
}

// The floor point, an emissive panel above it and three punctual lights of each type.
constexpr float kPanelRadiance = 3.0f;
const glm::vec3 kPoint(0.3f, 0.0f, 0.2f);
const glm::vec3 kCorner(-0.5f, 1.5f, -0.5f), kEdgeU(1.0f, 0.0f, 0.0f), kEdgeV(0.0f, 0.0f, 1.0f);  // faces -Y

scenes::Scene panel_and_lights(int point_lights) {
  std::vector<scenes::PunctualLight> lights;
  for (int i = 0; i < point_lights; ++i)
    lights.push_back(make_light(Type::Point, 0.5f + 0.1f * float(i % 7), glm::vec3(-3.0f + 0.09f * float(i), 2.5f, 1.0f)));
  // Both beside the panel, not behind it; the point is on the spot's ramp.
  scenes::PunctualLight spot = make_light(Type::Spot, 4.0f, glm::vec3(1.5f, 2.0f, 0.2f), glm::vec3(-0.5f, -1.0f, 0.0f));
  spot.inner_cone_angle = 0.05f;
  spot.outer_cone_angle = 0.15f;
  lights.push_back(spot);
  lights.push_back(make_light(Type::Directional, 2.0f, glm::vec3(0.0f), glm::vec3(-1.0f, -1.0f, 0.0f)));
  scenes::Scene scene = floor_with(lights);
  const int panel = test::add_material(scene, test::make_emitter(glm::vec3(kPanelRadiance)));
  test::add_quad(scene, kCorner, kEdgeU, kEdgeV, panel, "panel");
  return scene;
}

double expected_irradiance(const scenes::Scene& scene) {
  std::vector<glm::dvec3> polygon;
  for (const glm::vec3& v : {kCorner, kCorner + kEdgeU, kCorner + kEdgeU + kEdgeV, kCorner + kEdgeV})
    polygon.push_back(glm::dvec3(v - kPoint));
  double sum = test::polygon_irradiance(polygon, glm::dvec3(0, 1, 0), kPanelRadiance);
  for (const scenes::PunctualLight& l : scene.lights) {
    const double watts = l.intensity / scenes::PunctualLight::kLumensPerWatt;
    if (l.type == Type::Directional) {
      sum += watts * -l.direction.y;
      continue;
    }
    const glm::vec3 to_point = glm::normalize(kPoint - l.position);
    const double falloff = l.type == Type::Spot ? l.spot_falloff(glm::dot(l.direction, to_point)) : 1.0;
    sum += point_irradiance(watts, l.position, kPoint) * falloff;
  }
  return sum;
}

// Light samples alone (spatial choice with 2 + 3 lights; power choice with 2 + 70 > 64).
TEST(DeltaLights, ChosenWithEmissiveTrianglesTheEstimateIsUnbiased) {
  for (int point_lights : {1, 70}) {
    const scenes::Scene scene = panel_and_lights(point_lights);
    const RenderScene rs(scene);
    Rng rng(11, uint64_t(point_lights));
    const test::MeanAndError m = test::monte_carlo(200000, [&](int) {
      const float u = rng.next_float();
      return irradiance_sample(rs, kPoint, u, rng.next_2d());
    });
    const double expected = expected_irradiance(scene);
    EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + 1e-3 * expected) << point_lights << " point lights";
  }
}

// MIS against cosine rays: the panel's weights must include the probability of choosing it
// over the punctual lights, or the two strategies no longer sum to one.
TEST(DeltaLights, MisWithCosineRaysStillSumsToOne) {
  for (int point_lights : {1, 70}) {
    const scenes::Scene scene = panel_and_lights(point_lights);
    const RenderScene rs(scene);
    Rng rng(12, uint64_t(point_lights));
    const ShadingPoint x = floor_point(kPoint);
    const test::MeanAndError m = test::monte_carlo(200000, [&](int) {
      const float u = rng.next_float();
      double sum = irradiance_sample(rs, kPoint, u, rng.next_2d(), true);
      const glm::vec3 local = sample_cosine_hemisphere(rng.next_2d());
      SurfaceInteraction si;
      if (rs.trace(Ray{kPoint + 1e-4f * x.geometric_normal, x.frame.to_world(local)}, &si) && si.emits)
        sum += kPi * si.emission.y * emitter_hit_weight(rs, kPoint, local.z * kInvPi, si);
      return sum;
    });
    const double expected = expected_irradiance(scene);
    EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + 1e-3 * expected) << point_lights << " point lights";
  }
}

TEST(DeltaLights, DegenerateLightsGiveZerosNotNaN) {
  scenes::PunctualLight on_floor = make_light(Type::Point, 1.0f, glm::vec3(0.0f));     // at the shaded point
  scenes::PunctualLight huge = make_light(Type::Point, 3e37f, glm::vec3(0, 1e-19f, 0));  // irradiance overflows
  scenes::PunctualLight dark = make_light(Type::Point, 0.0f, glm::vec3(0, 1, 0));
  scenes::PunctualLight hard_spot = make_light(Type::Spot, 1.0f, glm::vec3(0, 1, 0));
  hard_spot.inner_cone_angle = hard_spot.outer_cone_angle = 0.4f;
  scenes::PunctualLight grazing = make_light(Type::Directional, 1.0f, glm::vec3(0.0f), glm::vec3(1, 0, 0));
  for (const scenes::PunctualLight& light : {on_floor, huge, dark, hard_spot, grazing}) {
    const RenderScene rs(floor_with({light}));
    Rng rng(13, 0);
    for (int i = 0; i < 100; ++i) {
      const glm::vec3 p(rng.next_float() - 0.5f, 0.0f, rng.next_float() - 0.5f);
      const double e = irradiance_sample(rs, i == 0 ? glm::vec3(0.0f) : p, rng.next_float(), rng.next_2d());
      ASSERT_TRUE(std::isfinite(e) && e >= 0.0) << to_string(light.type) << " " << e;
    }
  }
}

// Camera ray -> floor -> one scattering event: exactly f cos E for a scene lit only by a
// point light (the kernel must run next-event estimation although nothing emits).
TEST(DeltaLights, PathTracerSamplesPunctualLightsAlone) {
  const glm::vec3 lamp(0.0f, 2.0f, 0.0f);
  const scenes::Scene scene = floor_with({make_light(Type::Point, 3.0f, lamp)});
  const RenderScene rs(scene);
  const Effects effects = analyse_effects(scene, false);
  ASSERT_TRUE(effects.punctual_lights);
  ASSERT_FALSE(effects.emitters);
  PathSettings settings;
  settings.max_bounces = 1;
  const PathTracer tracer(rs, effects, settings);
  const glm::vec3 eye(1.0f, 1.0f, 0.5f), target(0.5f, 0.0f, 0.0f);
  const Ray ray{eye, glm::normalize(target - eye)};
  PathCounters counters;
  const glm::vec3 L = tracer.radiance(ray, 7, &counters);
  const Frame frame(glm::vec3(0, 1, 0));
  const glm::vec3 wi = glm::normalize(lamp - target);
  const glm::vec3 f = brdf_eval(BrdfParams{glm::vec3(0.5f), 1.0f, 0.0f}, frame.to_local(-ray.direction), frame.to_local(wi));
  const float expected = f.x * float(point_irradiance(3.0, lamp, target));
  EXPECT_NEAR(L.x, expected, 1e-4f * expected);
}

}  // namespace
}  // namespace phyir::render
