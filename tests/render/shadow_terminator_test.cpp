// The shadow terminator of smooth-shaded low-polygon meshes (docs/brdf.md, "Smooth normals
// on coarse meshes"): a faceted sphere with interpolated normals under a point light is
// lit as the smooth sphere its normals describe, up to its shading horizon, and not
// beyond; a flat wall with a light behind it stays dark whatever its shading normal says; a
// thin plate whose normals are smoothed over its rim keeps the shadow of a card above it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "phyir/core/safe_math.h"
#include "phyir/render/brdf.h"
#include "phyir/render/direct_lighting.h"
#include "phyir/render/frame.h"
#include "phyir/render/render_view.h"
#include "phyir/render/rng.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

constexpr int kSize = 96;
constexpr float kWatts = 16.0f;  // W/sr

// The direction at azimuth phi (degrees) about +Y, as add_uv_sphere lays out its columns
// (x = sin phi, z = cos phi).
glm::vec3 azimuth(float degrees) {
  const float phi = glm::radians(degrees);
  return glm::vec3(std::sin(phi), 0.0f, std::cos(phi));
}

// The light at azimuth 105 degrees puts the terminator at 15 degrees, the middle of a
// column of a 12-segment sphere's facets: there the facets lean away from the light, which
// is below their plane over half the facet while above the interpolated normal's horizon
// (at a column of vertices instead, the facets lean towards it and nothing shows).
const glm::vec3 kLight = 4.0f * azimuth(105.0f);

// A perspective camera facing the terminator (azimuth 15 degrees): it runs down the middle
// of the image.
CameraModel camera() {
  CameraModel c;
  c.projection = Projection::Perspective;
  c.position = 2.5f * azimuth(15.0f);
  c.forward = -azimuth(15.0f);
  c.yfov = 0.5f;
  c.width = c.height = kSize;
  return c;
}

// Direct light only: what the first hit receives from the point light.
RenderSettings direct_only() {
  RenderSettings s;
  s.spp = 16;
  s.seed = 3;
  s.progress = false;
  s.path.max_bounces = 1;
  return s;
}

struct Band {
  double rendered = 0.0, smooth = 0.0;
  int pixels = 0;
};

// Renders a sphere of `segments` x `rings` and sums, over the pixels whose shading normal
// n has n.l in [lo, hi), the rendered radiance and the smooth sphere's: the BRDF in n's
// frame times the light's irradiance at the hit point.
Band terminator_band(int segments, int rings, float lo, float hi) {
  scenes::Scene scene;
  scene.source = "shadow_terminator_test";
  const scenes::Material white = test::make_material(glm::vec3(0.8f), 1.0f, 0.0f);
  test::add_uv_sphere(scene, glm::vec3(0.0f), 0.5f, test::add_material(scene, white), segments, rings);
  scene.lights.push_back(test::make_point_light(kWatts, kLight));
  const RenderScene rs(scene);
  const CameraModel cam = camera();
  const RenderOutput out = render_view(rs, cam, direct_only());
  const Image color = out.film.color();
  const BrdfParams brdf{glm::vec3(0.8f), 1.0f, 0.0f};
  Band band;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      if (out.film.aov("mask_geometry").at(x, y) == 0.0f) continue;
      const Ray ray = cam.generate_ray(glm::vec2(x + 0.5f, y + 0.5f));
      const glm::vec3 p = ray.origin + ray.direction * out.film.aov("depth").at(x, y);
      const glm::vec3 n(out.film.aov("normal").at(x, y, 0), out.film.aov("normal").at(x, y, 1),
                        out.film.aov("normal").at(x, y, 2));
      const glm::vec3 to_light = kLight - p;
      const float r2 = glm::dot(to_light, to_light);
      const glm::vec3 l = to_light / std::sqrt(r2);
      const float cosine = glm::dot(n, l);
      if (!(cosine >= lo && cosine < hi)) continue;
      const Frame frame(n);
      const glm::vec3 f = brdf_eval(brdf, frame.to_local(-ray.direction), frame.to_local(l));
      band.smooth += double(f.y) * kWatts * std::max(cosine, 0.0f) / r2;
      band.rendered += color.at(x, y, 1);
      ++band.pixels;
    }
  }
  return band;
}

TEST(ShadowTerminator, FacetedSphereIsLitAsTheSmoothSphereUpToItsShadingHorizon) {
  // 12 x 6 facets: 30 degrees each, so near the terminator the light is up to 15 degrees
  // below a facet's plane while above the interpolated normal's horizon.
  for (const auto& [lo, hi] : {std::pair{0.02f, 0.15f}, std::pair{0.15f, 0.35f}, std::pair{0.5f, 1.01f}}) {
    const Band band = terminator_band(12, 6, lo, hi);
    std::printf("[terminator] 12 x 6 sphere, n.l in [%.2f, %.2f): rendered / smooth %.3f over %d pixels\n", lo, hi,
                band.rendered / band.smooth, band.pixels);
    ASSERT_GT(band.pixels, 20) << lo;
    EXPECT_NEAR(band.rendered / band.smooth, 1.0, 0.1) << "n.l in [" << lo << ", " << hi << "): "
                                                        << band.pixels << " pixels";
  }
}

TEST(ShadowTerminator, NothingBeyondTheShadingHorizon) {
  // Pixels whose centre is beyond the horizon: only the edge of their footprint, on the
  // sphere's silhouette, may catch light; on average less than 1e-4 of a lit pixel's ~0.25.
  const Band band = terminator_band(12, 6, -1.0f, -0.05f);
  ASSERT_GT(band.pixels, 20);
  EXPECT_LT(band.rendered / band.pixels, 2.5e-5);
}

TEST(ShadowTerminator, AFinelyTessellatedSphereAgreesToo) {
  const Band band = terminator_band(96, 48, 0.02f, 0.15f);
  ASSERT_GT(band.pixels, 20);
  EXPECT_NEAR(band.rendered / band.smooth, 1.0, 0.05);
}

TEST(ShadowTerminator, AWallWithALightBehindItStaysDark) {
  // A one-quad wall (z = 0, facing +z) whose vertex normals lean 30 degrees towards +x, and
  // a point light behind it (z < 0) but in front of the leaning normals: the geometric
  // surface is between them, so no light reaches the visible side (a renderer that let
  // shadow rays skip the triangle they leave, as Cycles does, would light it).
  scenes::Scene scene;
  scene.source = "shadow_terminator_test: wall";
  const int white = test::add_material(scene, test::make_material(glm::vec3(0.8f)));
  // Wide enough that the light is behind it from every point in view.
  const int wall = test::add_quad(scene, glm::vec3(-2, -2, 0), glm::vec3(12, 0, 0), glm::vec3(0, 4, 0), white, "wall");
  for (glm::vec3& n : scene.meshes[wall].normals) n = glm::normalize(glm::vec3(0.5f, 0.0f, 0.866f));
  scene.lights.push_back(test::make_point_light(kWatts, glm::vec3(3.0f, 0.0f, -0.3f)));
  const RenderScene rs(scene);
  const Image color = render_view(rs, camera(), direct_only()).film.color();
  for (float v : color.pixels) ASSERT_EQ(v, 0.0f);
}

// A bell-shaped lampshade (a surface of revolution about +Y, open at both ends, double-sided,
// smooth normals): radius r(y) = 0.08 + 0.17 (1 - y / 0.3)^2 from its rim (y = 0, r = 0.25)
// to its top (y = 0.3). Along a meridian the inside bulges towards the axis (convex seen from
// the bulb), around the axis it is concave: both cases of the terminator at once.
int add_shade(scenes::Scene& scene, int material, int segments, int rings) {
  scenes::Mesh mesh;
  mesh.name = "shade";
  mesh.material = material;
  const float pi = 3.14159265358979323846f;
  for (int r = 0; r <= rings; ++r) {
    const float y = 0.3f * float(r) / float(rings);
    const float s = 1.0f - y / 0.3f;
    const float radius = 0.08f + 0.17f * s * s;
    const float slope = -2.0f * 0.17f * s / 0.3f;  // dr/dy
    for (int k = 0; k <= segments; ++k) {
      const float phi = 2.0f * pi * float(k) / float(segments);
      const glm::vec3 radial(std::cos(phi), 0.0f, std::sin(phi));
      mesh.positions.push_back(radial * radius + glm::vec3(0.0f, y, 0.0f));
      mesh.normals.push_back(glm::normalize(radial - glm::vec3(0.0f, slope, 0.0f)));  // outward
    }
  }
  const unsigned stride = unsigned(segments + 1);
  for (int r = 0; r < rings; ++r) {
    for (int k = 0; k < segments; ++k) {
      const unsigned a = r * stride + k, b = a + 1, c = a + stride, d = c + 1;
      mesh.triangles.push_back(glm::uvec3(a, c, b));  // wound outward
      mesh.triangles.push_back(glm::uvec3(b, c, d));
    }
  }
  return test::add_mesh(scene, std::move(mesh));
}

// The mean radiance of the shade's inside, seen from below on its axis, lit only by a point
// light on the axis 0.16 m above the rim (the pendant of docs/cycles-comparison.md).
double shade_inside(int segments, int rings) {
  scenes::Scene scene;
  scene.source = "shadow_terminator_test: shade";
  scenes::Material fabric = test::make_material(glm::vec3(0.8f));
  fabric.double_sided = true;
  add_shade(scene, test::add_material(scene, fabric), segments, rings);
  scene.lights.push_back(test::make_point_light(1.0f, glm::vec3(0.0f, 0.16f, 0.0f)));
  const RenderScene rs(scene);
  CameraModel c;
  c.projection = Projection::Perspective;
  c.position = glm::vec3(0.0f, -0.3f, 0.0f);
  c.forward = glm::vec3(0.0f, 1.0f, 0.0f);
  c.up = glm::vec3(0.0f, 0.0f, 1.0f);
  c.yfov = 1.4f;
  c.width = c.height = kSize;
  const Image color = render_view(rs, c, direct_only()).film.color();
  double sum = 0.0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) sum += color.at(x, y, 1);
  return sum / (kSize * kSize);
}

TEST(ShadowTerminator, ACoarseLampshadeIsLitAsAFineOne) {
  const double coarse = shade_inside(12, 4), fine = shade_inside(192, 64);
  std::printf("[terminator] lampshade inside: 12 x 4 facets %.5g, 192 x 64 facets %.5g (ratio %.3f)\n", coarse,
              fine, coarse / fine);
  ASSERT_GT(fine, 0.0);
  EXPECT_NEAR(coarse / fine, 1.0, 0.1);
}

// A thin plate (0.4 x 0.4 m, 2 mm thick) whose vertex normals are smoothed over its rim, as
// exported lamp plates and shelves often are: every corner's normal leans 55 degrees off the
// top face, so the smooth surface they describe bulges 20 cm above its middle. A 10 cm card
// hangs 2 cm above the middle, under a point light and a small emissive panel straight above:
// the middle is in the card's shadow. The light is far above the facet's plane, where the
// facet hides nothing and a BRDF-sampled ray from the point itself would see the card, so the
// shadow rays leave from the point, not from the bulge (from there they passed over the card).
TEST(ShadowTerminator, AThinPlateWithNormalsSmoothedOverItsRimKeepsItsShadows) {
  scenes::Scene scene;
  scene.source = "shadow_terminator_test: plate";
  const int white = test::add_material(scene, test::make_material(glm::vec3(0.8f)));
  scenes::Mesh plate;
  plate.name = "plate";
  plate.material = white;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 sign(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f, corner & 4 ? 1.0f : -1.0f);
    plate.positions.push_back(sign * glm::vec3(0.2f, 0.001f, 0.2f));
    plate.normals.push_back(glm::normalize(sign));  // the three faces' normals averaged
  }
  // Six faces, wound outward.
  const unsigned faces[6][4] = {{2, 6, 7, 3}, {0, 1, 5, 4}, {1, 3, 7, 5}, {0, 4, 6, 2}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  for (const auto& f : faces) {
    plate.triangles.push_back(glm::uvec3(f[0], f[1], f[2]));
    plate.triangles.push_back(glm::uvec3(f[0], f[2], f[3]));
  }
  test::add_mesh(scene, std::move(plate));
  test::add_quad(scene, glm::vec3(-0.05f, 0.021f, -0.05f), glm::vec3(0.1f, 0, 0), glm::vec3(0, 0, 0.1f), white, "card");
  scene.lights.push_back(test::make_point_light(kWatts, glm::vec3(0.0f, 1.0f, 0.0f)));
  test::add_quad(scene, glm::vec3(-0.02f, 1.0f, 0.02f), glm::vec3(0.04f, 0, 0), glm::vec3(0, 0, -0.04f),
                 test::add_material(scene, test::make_emitter(glm::vec3(50.0f))), "panel");  // faces down
  const RenderScene rs(scene);

  SurfaceInteraction si;
  ASSERT_TRUE(rs.trace(Ray{glm::vec3(0.01f, 0.015f, 0.0f), glm::vec3(0, -1, 0)}, &si));
  ASSERT_GT(glm::length(si.shadow_lift), 0.1f) << "the plate's smoothed normals lift its middle";
  const ShadingPoint x = shading_point(si, glm::vec3(0, 1, 0));
  PathCounters counters;
  EXPECT_EQ(max_component(punctual_light(rs, x, Lobes::kAll, &counters)), 0.0f) << "the bulb, through the card";
  Rng rng(5, 1);
  DirectLightOptions options;
  for (int k = 0; k < 256; ++k) {
    LightVariates u;
    u.select = rng.next_float();
    u.point = rng.next_2d();
    ASSERT_EQ(max_component(sample_emitter_light(rs, x, u, options, glm::vec3(1.0f), &rng, &counters)), 0.0f)
        << "the panel, through the card (sample " << k << ")";
  }
}

}  // namespace
}  // namespace phyir::render
