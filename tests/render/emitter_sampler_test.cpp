// Next-event estimation on emissive triangles: the solid-angle pdf against analytic solid
// angles, its normalisation over the sphere, sample() == pdf(), power-proportional
// selection, solid-angle sampling of a strip light beside the point, one-sided emission and
// textured emitters.
#include "phyir/render/emitter_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>
#include <vector>

#include "phyir/core/safe_math.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "monte_carlo.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

using test::add_material;
using test::add_quad;
using test::add_texture;
using test::add_uv_sphere;
using test::mesh_solid_angle;
using test::make_emitter;

using test::MeanAndError;
using test::monte_carlo;

// A 1 m x 0.5 m ceiling light at y = 2 facing down (-Y).
int add_ceiling_light(scenes::Scene& scene, int material) {
  return add_quad(scene, {-0.5f, 2.0f, -0.25f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.5f}, material, "ceiling light");
}

TEST(EmitterSampler, ExpectedInversePdfIsTheAnalyticSolidAngle) {
  scenes::Scene scene;
  const int light = add_ceiling_light(scene, add_material(scene, make_emitter(glm::vec3(5.0f))));
  const EmitterSampler sampler(scene);
  ASSERT_EQ(sampler.emissive_triangle_count(), 2u);
  // Centred rectangle a x b at distance d: 4 asin(a b / sqrt((a^2 + 4 d^2)(b^2 + 4 d^2))).
  const double centred = 4.0 * std::asin(0.5 / std::sqrt((1.0 + 16.0) * (0.25 + 16.0)));
  EXPECT_NEAR(mesh_solid_angle(scene.meshes[light], {0, 0, 0}), centred, 1e-9);

  const glm::vec3 references[] = {{0, 0, 0}, {1.5f, 0.3f, 0.7f}, {0.1f, 1.9f, 0.05f}, {-3.0f, 1.5f, 2.0f}};
  for (const glm::vec3& ref : references) {
    const double analytic = mesh_solid_angle(scene.meshes[light], ref);
    Rng rng(17, 5);
    const MeanAndError est = monte_carlo(200000, [&](int) {
      EmitterSample s;
      if (!sampler.sample(ref, rng.next_float(), rng.next_2d(), &s)) return 0.0;
      return 1.0 / double(s.pdf);
    });
    EXPECT_NEAR(est.mean, analytic, 4.0 * est.standard_error + 1e-6 * analytic)
        << "reference (" << ref.x << ", " << ref.y << ", " << ref.z << ")";
    EXPECT_NEAR(est.mean / analytic, 1.0, 0.01);
    std::cout << "solid angle from (" << ref.x << ", " << ref.y << ", " << ref.z << "): analytic " << analytic
              << ", E[1/pdf] " << est.mean << " +- " << est.standard_error << "\n";
  }
}

// Lights of several kinds: two quads, an emissive sphere and a textured quad, and a point
// light if asked.
scenes::Scene mixed_lights(bool point_light = false) {
  scenes::Scene scene;
  add_ceiling_light(scene, add_material(scene, make_emitter(glm::vec3(5.0f))));
  add_quad(scene, {2.0f, 0.5f, -1.0f}, {0.0f, 0.0f, 2.0f}, {0.0f, 1.0f, 0.0f}, add_material(scene, make_emitter({1, 2, 3})),
           "wall light");  // faces -X
  add_uv_sphere(scene, {-2.0f, 1.0f, 0.5f}, 0.3f, add_material(scene, make_emitter(glm::vec3(2.0f))), 24, 12);
  scenes::Material textured = make_emitter(glm::vec3(4.0f), true);
  textured.emissive_texture.texture = add_texture(scene, 2, 1, {{1, 0, 0, 1}, {0, 0, 1, 1}});
  add_quad(scene, {-1.0f, 0.5f, -2.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, add_material(scene, textured),
           "textured light");  // faces +Z, double-sided
  if (point_light) scene.lights = {test::make_point_light(4.0f, glm::vec3(0.3f, 1.2f, 0.2f))};
  return scene;
}

// With a point light too, choosing among the punctual lights or (punctual = false) not: that
// sampler never returns the point light, and pdf() asked the same way agrees.
TEST(EmitterSampler, SamplePdfEqualsPdfForTheSamePoint) {
  for (const bool punctual : {true, false}) {
  const scenes::Scene scene = mixed_lights(!punctual);
  const EmitterSampler sampler(scene);
  Rng rng(23, 1);
  int mismatches = 0, samples = 0;
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 ref(3.0f * rng.next_float() - 1.5f, 1.8f * rng.next_float(), 3.0f * rng.next_float() - 1.5f);
    EmitterSample s;
    if (!sampler.sample(ref, rng.next_float(), rng.next_2d(), &s, punctual)) continue;
    ++samples;
    if (s.delta) ++mismatches;
    const float p = sampler.pdf(ref, s.mesh, s.triangle, s.position, punctual);
    if (!(std::abs(p - s.pdf) <= 1e-6f * s.pdf)) ++mismatches;
    // The sample's geometry is self-consistent.
    if (std::abs(glm::length(s.position - ref) - s.distance) > 1e-5f * s.distance) ++mismatches;
    if (glm::length(s.wi - (s.position - ref) / s.distance) > 1e-5f) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0) << "punctual " << punctual;
  EXPECT_GT(samples, 99000) << "punctual " << punctual;
  // Non-emissive or unknown triangles have pdf 0.
  EXPECT_EQ(sampler.pdf({0, 0, 0}, 99, 0, {0, 2, 0}, punctual), 0.0f);
  EXPECT_EQ(sampler.pdf({0, 0, 0}, 0, 7, {0, 2, 0}, punctual), 0.0f);
  }
}

TEST(EmitterSampler, PdfIntegratesToOneOverTheSphere) {
  // Uniform directions from a reference point; every emitter point along each ray (all
  // surfaces, not just the first: the sampler also picks the far side of the sphere)
  // contributes pdf / (1 / 4 pi). The mean must be 1, also with a point light in the scene
  // when the sampler leaves the punctual lights out (punctual = false); with them, 1 less
  // the point light's share.
  for (const bool point_light : {false, true}) {
  const scenes::Scene scene = mixed_lights(point_light);
  const RenderScene rs(scene);
  const glm::vec3 ref(0.2f, 0.8f, -0.3f);
  Rng rng(31, 7);
  const MeanAndError est = monte_carlo(400000, [&](int) {
    const glm::vec3 d = sample_uniform_sphere(rng.next_2d());
    double sum = 0.0;
    Ray ray{ref, d};
    SurfaceInteraction si;
    for (int bounce = 0; bounce < 8 && rs.trace(ray, &si); ++bounce) {
      sum += rs.emitters().pdf(ref, si.mesh, si.triangle, si.position, !point_light);
      ray.origin = spawn_origin(si.position, si.geometric_normal, d);
    }
    return sum / double(uniform_sphere_pdf());
  });
  std::cout << "integral of the emitter pdf over the sphere (point light " << point_light << "): " << est.mean
            << " +- " << est.standard_error << "\n";
  EXPECT_NEAR(est.mean, 1.0, 4.0 * est.standard_error);
  EXPECT_NEAR(est.mean, 1.0, 0.02);
  if (!point_light) continue;
  // The same sampler choosing among the point light too: its triangles' pdf integrates to
  // less, by the point light's probability of being chosen.
  Rng again(31, 7);
  const MeanAndError with_light = monte_carlo(100000, [&](int) {
    const glm::vec3 d = sample_uniform_sphere(again.next_2d());
    SurfaceInteraction si;
    return rs.trace(Ray{ref, d}, &si) ? double(rs.emitters().pdf(ref, si.mesh, si.triangle, si.position)) /
                                            double(rs.emitters().pdf(ref, si.mesh, si.triangle, si.position, false))
                                      : 1.0;
  });
  EXPECT_LT(with_light.mean, 0.99);
  }
}

double fraction_picking_mesh(const EmitterSampler& sampler, int mesh, int n, const glm::vec3& reference) {
  Rng rng(3, 3);
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    EmitterSample s;
    if (sampler.sample(reference, rng.next_float(), rng.next_2d(), &s) && s.mesh == mesh) ++hits;
  }
  return double(hits) / n;
}

// Selection is power / distance^2 per cluster: seen from a point equidistant from both
// lights' centres it is power alone.
TEST(EmitterSampler, LightsArePickedInProportionToPower) {
  const int n = 200000;
  const double sigma = std::sqrt(0.75 * 0.25 / n);
  {  // Equal areas, radiance 3 : 1.
    scenes::Scene scene;
    const int bright = add_quad(scene, {-1, 2, -1}, {1, 0, 0}, {0, 0, 1}, add_material(scene, make_emitter(glm::vec3(3.0f))));
    add_quad(scene, {0.5f, 2, -1}, {1, 0, 0}, {0, 0, 1}, add_material(scene, make_emitter(glm::vec3(1.0f))));
    const EmitterSampler sampler(scene);
    EXPECT_NEAR(sampler.total_power(), 3.0f + 1.0f, 1e-5f);
    const double f = fraction_picking_mesh(sampler, bright, n, {0.25f, -50.0f, -0.5f});
    std::cout << "radiance 3:1 -> picked " << f << " : " << 1 - f << "\n";
    EXPECT_NEAR(f, 0.75, 4.0 * sigma);
  }
  {  // Equal radiance, areas 3 : 1.
    scenes::Scene scene;
    const int mat = add_material(scene, make_emitter(glm::vec3(1.0f)));
    const int big = add_quad(scene, {-4, 2, -1}, {3, 0, 0}, {0, 0, 1}, mat);
    add_quad(scene, {0.5f, 2, -1}, {1, 0, 0}, {0, 0, 1}, mat);
    const EmitterSampler sampler(scene);
    EXPECT_NEAR(fraction_picking_mesh(sampler, big, n, {-0.75f, -50.0f, -0.5f}), 0.75, 4.0 * sigma);
  }
  {  // Equal factors, emissive textures of mean luminance 1.5 : 0.5 (grey texels).
    scenes::Scene scene;
    scenes::Material a = make_emitter(glm::vec3(1.0f)), b = a;
    a.emissive_texture.texture = add_texture(scene, 2, 1, {{1, 1, 1, 1}, {2, 2, 2, 1}});
    b.emissive_texture.texture = add_texture(scene, 2, 1, {{0, 0, 0, 1}, {1, 1, 1, 1}});
    const int brighter = add_quad(scene, {-1, 2, -1}, {1, 0, 0}, {0, 0, 1}, add_material(scene, a));
    add_quad(scene, {0.5f, 2, -1}, {1, 0, 0}, {0, 0, 1}, add_material(scene, b));
    const EmitterSampler sampler(scene);
    EXPECT_NEAR(fraction_picking_mesh(sampler, brighter, n, {0.25f, -50.0f, -0.5f}), 0.75, 4.0 * sigma);
  }
}

TEST(EmitterSampler, NearerAndFacingLightsArePickedMore) {
  scenes::Scene scene;
  const int mat = add_material(scene, make_emitter(glm::vec3(1.0f)));
  // Two equal down-facing lights at heights 2 and 4 above the origin, and one facing up
  // (away from any point below it).
  const int near_light = add_quad(scene, {-0.5f, 2, -0.5f}, {1, 0, 0}, {0, 0, 1}, mat);
  const int far_light = add_quad(scene, {3.5f, 4, -0.5f}, {1, 0, 0}, {0, 0, 1}, mat);
  const int up_light = add_quad(scene, {-0.5f, 1, 3.0f}, {0, 0, 1}, {1, 0, 0}, mat);
  const EmitterSampler sampler(scene);
  ASSERT_EQ(sampler.cluster_count(), 3u);
  const int n = 100000;
  EXPECT_EQ(fraction_picking_mesh(sampler, up_light, n, {0, 0, 0}), 0.0);
  // Weights cos_bound / d^2 to the centres: the near light is straight above (cos 1,
  // d^2 = 4); the far one has d^2 = 4^2 + 4^2 and cos bound 4 / |(3.5, 4, 0)| at the
  // nearest point of its bounds.
  const double w_near = 1.0 / 4.0, w_far = 4.0 / std::sqrt(3.5 * 3.5 + 16.0) / 32.0;
  const double p_near = w_near / (w_near + w_far);
  EXPECT_NEAR(fraction_picking_mesh(sampler, near_light, n, {0, 0, 0}), p_near, 4.0 * std::sqrt(0.1 / n));
  EXPECT_NEAR(fraction_picking_mesh(sampler, far_light, n, {0, 0, 0}), 1.0 - p_near, 4.0 * std::sqrt(0.1 / n));
  // Above every light only the up-facing one can light the point.
  EXPECT_EQ(fraction_picking_mesh(sampler, up_light, n, {0, 5.0f, 3.5f}), 1.0);
}

// Selection weights are kept per thread for the last point asked about: samplers of two
// scenes asked about the same point in turn must each get their own, and a new point new ones.
TEST(EmitterSampler, EachSamplerGetsItsOwnSelectionAtTheSamePoint) {
  scenes::Scene two, one;
  const int mat_two = add_material(two, make_emitter(glm::vec3(1.0f)));
  const int near_two = add_quad(two, {-0.5f, 2, -0.5f}, {1, 0, 0}, {0, 0, 1}, mat_two);
  add_quad(two, {3.5f, 4, -0.5f}, {1, 0, 0}, {0, 0, 1}, mat_two);
  const int mat_one = add_material(one, make_emitter(glm::vec3(1.0f)));
  const int near_one = add_quad(one, {-0.5f, 2, -0.5f}, {1, 0, 0}, {0, 0, 1}, mat_one);
  add_quad(one, {3.5f, 40, -0.5f}, {1, 0, 0}, {0, 0, 1}, mat_one);
  const EmitterSampler sampler_two(two), sampler_one(one);
  const glm::vec3 at(0.0f), light_point(0.0f, 2.0f, 0.0f);
  auto pdfs = [&] {
    return std::make_pair(sampler_two.pdf(at, near_two, 0, light_point), sampler_one.pdf(at, near_one, 0, light_point));
  };
  const auto first = pdfs();
  EXPECT_GT(first.second, first.first);  // the other light is 10 times further in `one`
  for (int k = 0; k < 3; ++k) EXPECT_EQ(pdfs(), first);
  // Another point in between, then the first again: the same values.
  EXPECT_NE(sampler_two.pdf(glm::vec3(3.5f, 0, 0), near_two, 0, light_point), first.first);
  EXPECT_EQ(sampler_two.pdf(at, near_two, 0, light_point), first.first);
}

// The edge of a ceiling fixture seen from the ceiling beside it: a 60 cm x 2 mm strip
// facing the point, 3 cm below it and 10 cm away. Light samples uniform in solid angle give
// Lambert's irradiance with a small spread; uniform points on the strip's area (what the
// sampler did before) have a spread several times larger, from the rare samples on its
// nearest part.
TEST(EmitterSampler, AStripLightBesideThePointIsSampledInSolidAngle) {
  scenes::Scene scene;
  const float Le = 20.0f;
  // cross(edge_u, edge_v) = +X: faces the point at x = 0.1.
  const glm::vec3 corner(0.0f, -0.032f, 0.3f), edge_u(0.0f, 0.0f, -0.6f), edge_v(0.0f, 0.002f, 0.0f);
  add_quad(scene, corner, edge_u, edge_v, add_material(scene, make_emitter(glm::vec3(Le))), "strip");
  const RenderScene render_scene(scene);
  const EmitterSampler& sampler = render_scene.emitters();
  const glm::vec3 point(0.1f, 0.0f, 0.05f), normal(0.0f, -1.0f, 0.0f);  // a ceiling point, facing down
  std::vector<glm::dvec3> polygon;
  for (const glm::vec3& v : {corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v})
    polygon.push_back(glm::dvec3(v - point));
  const double exact = test::polygon_irradiance(polygon, glm::dvec3(normal), Le);
  constexpr int n = 20000;
  Rng rng(11, 0);
  const MeanAndError solid = monte_carlo(n, [&](int) {
    EmitterSample ls;
    const float u = rng.next_float();
    if (!sampler.sample(point, u, rng.next_2d(), &ls)) return 0.0;
    return double(ls.radiance.x) * std::max(0.0, double(glm::dot(ls.wi, normal))) / double(ls.pdf);
  });
  const double strip_area = glm::length(glm::cross(edge_u, edge_v));
  const MeanAndError area = monte_carlo(n, [&](int) {
    const glm::vec2 u = rng.next_2d();
    const glm::vec3 q = corner + u.x * edge_u + u.y * edge_v, d = q - point;
    const double r2 = glm::dot(d, d), r = std::sqrt(r2);
    const double cos_point = std::max(0.0, double(glm::dot(d, normal)) / r), cos_light = std::max(0.0, -double(d.x) / r);
    return Le * cos_point * cos_light / r2 * strip_area;
  });
  std::printf("[ strip light ] exact %.4f, solid angle %.4f +- %.4f, area %.4f +- %.4f (same count)\n", exact, solid.mean,
              solid.standard_error, area.mean, area.standard_error);
  EXPECT_NEAR(solid.mean, exact, 4.0 * solid.standard_error + 1e-3 * exact);
  EXPECT_NEAR(area.mean, exact, 4.0 * area.standard_error + 1e-3 * exact);
  EXPECT_LT(solid.standard_error, 0.5 * area.standard_error);
}

TEST(EmitterSampler, OneSidedEmitterIsDarkFromBehind) {
  for (const bool double_sided : {false, true}) {
    scenes::Scene scene;
    add_ceiling_light(scene, add_material(scene, make_emitter({1.0f, 2.0f, 3.0f}, double_sided)));
    const EmitterSampler sampler(scene);
    Rng rng(1, 1);
    int wrong = 0;
    for (int i = 0; i < 10000; ++i) {
      EmitterSample below, above;
      ASSERT_TRUE(sampler.sample({0.1f, 0.5f, 0.0f}, rng.next_float(), rng.next_2d(), &below));
      if (below.radiance != glm::vec3(1.0f, 2.0f, 3.0f)) ++wrong;
      if (below.normal != glm::vec3(0, -1, 0)) ++wrong;
      // From behind a one-sided light nothing is sampled (it cannot light the point, and a
      // ray reaching its back sees no emission, so no pdf is ever asked there).
      const bool sampled = sampler.sample({0.1f, 3.5f, 0.0f}, rng.next_float(), rng.next_2d(), &above);
      if (sampled != double_sided) ++wrong;
      if (double_sided && (above.radiance != glm::vec3(1.0f, 2.0f, 3.0f) || !(above.pdf > 0.0f))) ++wrong;
    }
    if (!double_sided) {
      EXPECT_EQ(sampler.pdf({0.1f, 3.5f, 0.0f}, 0, 0, {0.0f, 2.0f, 0.0f}), 0.0f);
    }
    EXPECT_EQ(wrong, 0) << "double_sided " << double_sided;
  }
}

// A point on a light (a glowing lamp shade shading its own surface) lies in its triangles'
// planes and sees them edge-on: they give it no light. Its own triangle was sampled at a
// distance of float noise, in a direction of float noise, with weights in the thousands.
TEST(EmitterSampler, APointOnALightSeesItsPlaneEdgeOn) {
  scenes::Scene scene;
  // A tilted panel (hit points off its plane by rounding alone) and a second light beside it.
  const glm::vec3 corner(-0.5f, 2.0f, -0.25f), u(1.0f, 0.13f, 0.07f), v(0.03f, 0.21f, 0.5f);
  const int light = add_quad(scene, corner, u, v, add_material(scene, make_emitter(glm::vec3(5.0f), true)), "panel");
  add_quad(scene, {-0.5f, 1.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}, add_material(scene, make_emitter(glm::vec3(1.0f), true)),
           "other light");
  const RenderScene rs(scene);
  const EmitterSampler& sampler = rs.emitters();
  Rng rng(41, 3);
  int on_own_plane = 0, other = 0;
  for (int i = 0; i < 2000; ++i) {
    // Points on the panel as rays find them.
    const glm::vec3 target = corner + (0.1f + 0.8f * rng.next_float()) * u + (0.1f + 0.8f * rng.next_float()) * v;
    const glm::vec3 from(0.0f, 0.5f, 0.0f);
    SurfaceInteraction si;
    ASSERT_TRUE(rs.trace(Ray{from, glm::normalize(target - from)}, &si));
    ASSERT_EQ(si.mesh, light);
    EmitterSample s;
    if (!sampler.sample(si.position, rng.next_float(), rng.next_2d(), &s)) continue;
    if (s.mesh == light) ++on_own_plane;
    else ++other;
    EXPECT_EQ(sampler.pdf(si.position, light, 0, corner + 0.3f * u + 0.2f * v), 0.0f);
  }
  EXPECT_EQ(on_own_plane, 0);
  EXPECT_GT(other, 500) << "the other light still lights the point";
}

// A copy of mesh `m` wound the other way, at the same place: a twin sheet.
int add_twin(scenes::Scene& scene, int m) {
  scenes::Mesh twin = scene.meshes[size_t(m)];
  twin.name += " twin";
  for (glm::uvec3& t : twin.triangles) std::swap(t.y, t.z);
  for (glm::vec3& n : twin.normals) n = -n;
  return test::add_mesh(scene, std::move(twin));
}

// Irradiance at `reference` (facing up) estimated by light sampling alone.
MeanAndError light_sampled_irradiance(const EmitterSampler& sampler, const glm::vec3& reference, uint64_t seed) {
  Rng rng(seed, 3);
  return monte_carlo(100000, [&](int) {
    EmitterSample s;
    if (!sampler.sample(reference, rng.next_float(), rng.next_2d(), &s) || !(s.pdf > 0.0f)) return 0.0;
    return double(luminance(s.radiance)) * std::max(0.0f, s.wi.y) / double(s.pdf);
  });
}

TEST(EmitterSampler, TwinTrianglesAreOneSheet) {
  const glm::vec3 below(0.3f, 0.0f, 0.1f);
  for (const bool double_sided : {true, false}) {
    scenes::Scene single, twinned;
    const int light = add_ceiling_light(single, add_material(single, make_emitter(glm::vec3(2.0f), double_sided)));
    add_ceiling_light(twinned, add_material(twinned, make_emitter(glm::vec3(2.0f), double_sided)));
    const int twin = add_twin(twinned, light);
    const EmitterSampler one(single), two(twinned);
    const MeanAndError expected = light_sampled_irradiance(one, below, 5);
    const MeanAndError got = light_sampled_irradiance(two, below, 5);
    if (double_sided) {
      // The twin is left out: the same triangles, so the same estimate bit for bit, and a
      // ray that hits the twin gets the kept triangle's density for MIS.
      EXPECT_EQ(two.emissive_triangle_count(), 2u);
      EXPECT_EQ(two.twin_triangle_count(), 2u);
      EXPECT_EQ(got.mean, expected.mean);
      const glm::vec3 point(0.1f, 2.0f, 0.05f);
      for (int t = 0; t < 2; ++t)
        EXPECT_EQ(two.pdf(below, twin, t, point), two.pdf(below, light, t, point)) << "triangle " << t;
      EXPECT_GT(two.pdf(below, twin, 0, point) + two.pdf(below, twin, 1, point), 0.0f);
    } else {
      // One-sided twins light opposite sides: both kept, each counted from its own side only.
      EXPECT_EQ(two.emissive_triangle_count(), 4u);
      EXPECT_EQ(two.twin_triangle_count(), 0u);
      EXPECT_NEAR(got.mean, expected.mean, 4.0 * std::hypot(got.standard_error, expected.standard_error));
    }
    std::cout << (double_sided ? "double" : "one") << "-sided twins: irradiance " << got.mean << " +- "
              << got.standard_error << ", single sheet " << expected.mean << "\n";
  }
}

TEST(EmitterSampler, TexturedEmitterRadianceFollowsTheTexture) {
  // Left half (u < 0.5) red, right half blue, nearest filtering, emission 4, strength 0.5.
  scenes::Scene scene;
  scenes::Material m = make_emitter(glm::vec3(4.0f));
  m.emissive_strength = 0.5f;
  m.emissive_texture.texture = add_texture(scene, 2, 1, {{1, 0, 0, 1}, {0, 0, 1, 1}});
  add_ceiling_light(scene, add_material(scene, m));  // u = x + 0.5
  const EmitterSampler sampler(scene);
  Rng rng(4, 4);
  int wrong = 0;
  for (int i = 0; i < 10000; ++i) {
    EmitterSample s;
    ASSERT_TRUE(sampler.sample({0, 0, 0}, rng.next_float(), rng.next_2d(), &s));
    const float u = s.position.x + 0.5f;
    if (std::abs(u - 0.5f) < 1e-4f) continue;  // on the texel boundary
    const glm::vec3 expected = u < 0.5f ? glm::vec3(2, 0, 0) : glm::vec3(0, 0, 2);
    if (glm::length(s.radiance - expected) > 1e-6f) ++wrong;
  }
  EXPECT_EQ(wrong, 0);
}

TEST(EmitterSampler, CutOutPartsOfMaskedEmittersAreDark) {
  // Alpha MASK with the left half (u < 0.5) transparent: rays pass there, so it must not
  // send light either.
  scenes::Scene scene;
  scenes::Material m = make_emitter(glm::vec3(3.0f));
  m.alpha_mode = scenes::AlphaMode::Mask;
  m.base_color_texture.texture = add_texture(scene, 2, 1, {{1, 1, 1, 0}, {1, 1, 1, 1}});
  add_ceiling_light(scene, add_material(scene, m));
  const EmitterSampler sampler(scene);
  Rng rng(6, 1);
  int wrong = 0;
  for (int i = 0; i < 10000; ++i) {
    EmitterSample s;
    ASSERT_TRUE(sampler.sample({0, 0, 0}, rng.next_float(), rng.next_2d(), &s));
    const float u = s.position.x + 0.5f;
    if (std::abs(u - 0.5f) < 1e-4f) continue;
    if (s.radiance != (u < 0.5f ? glm::vec3(0.0f) : glm::vec3(3.0f))) ++wrong;
  }
  EXPECT_EQ(wrong, 0);
}

TEST(EmitterSampler, DegenerateTrianglesAndEmptyScenes) {
  scenes::Scene scene;
  const int emitter = add_material(scene, make_emitter(glm::vec3(1.0f)));
  add_quad(scene, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, add_material(scene, test::make_material()));  // not emissive
  const int mesh = add_quad(scene, {0, 2, 0}, {1, 0, 0}, {0, 0, 1}, emitter);
  scene.meshes[mesh].positions.push_back({5, 5, 5});
  scene.meshes[mesh].normals.push_back({0, 1, 0});
  scene.meshes[mesh].tangents.push_back({1, 0, 0, 1});
  scene.meshes[mesh].texcoords0.push_back({0, 0});
  scene.meshes[mesh].triangles.push_back({4, 4, 4});  // zero area
  scene.meshes[mesh].triangles.push_back({0, 1, 9});  // index out of range
  const EmitterSampler sampler(scene);
  EXPECT_EQ(sampler.emissive_triangle_count(), 2u);
  EXPECT_EQ(sampler.pdf({0, 0, 0}, mesh, 2, {5, 5, 5}), 0.0f);
  EXPECT_EQ(sampler.pdf({0, 0, 0}, mesh, 3, {0, 2, 0}), 0.0f);
  EXPECT_GT(sampler.pdf({0.2f, 0, 0.2f}, mesh, 0, {0.5f, 2, 0.3f}), 0.0f);

  const scenes::Scene dark;
  const EmitterSampler none(dark);
  EXPECT_TRUE(none.empty());
  EmitterSample s;
  EXPECT_FALSE(none.sample({0, 0, 0}, 0.5f, {0.5f, 0.5f}, &s));
  EXPECT_EQ(none.pdf({0, 0, 0}, 0, 0, {0, 1, 0}), 0.0f);
  // A reference on the emitter's plane sees it edge-on: no valid sample.
  scenes::Scene flat;
  add_ceiling_light(flat, add_material(flat, make_emitter(glm::vec3(1.0f))));
  const EmitterSampler edge_on(flat);
  EXPECT_FALSE(edge_on.sample({3.0f, 2.0f, 0.0f}, 0.3f, {0.3f, 0.6f}, &s));
}

}  // namespace
}  // namespace phyir::render
