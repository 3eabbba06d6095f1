// Hard cases stay numerically stable: mirrors (roughness 0), metalness 1, grazing views,
// huge and tiny emitters, degenerate triangles and a camera on a surface. Every pixel of
// every image must be finite and non-negative, and no path sample may need zeroing.
#include <gtest/gtest.h>

#include <cmath>

#include "phyir/render/render_view.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

RenderSettings settings(int spp) {
  RenderSettings s;
  s.spp = spp;
  s.seed = 9;
  s.progress = false;
  return s;
}

void expect_all_finite(const RenderOutput& out) {
  EXPECT_EQ(out.stats.counters.nonfinite_samples, 0u);
  for (float v : out.film.color().pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << v;
  for (const std::string& name : Film::aov_names())
    for (float v : out.film.aov(name).pixels) ASSERT_TRUE(std::isfinite(v)) << name;
}

CameraModel panorama(const glm::vec3& p) {
  CameraModel c;
  c.position = p;
  c.width = 48;
  c.height = 24;
  return c;
}

// A room with every hard material: a mirror wall, white metal, glass, and the given light.
scenes::Scene hard_room(const glm::vec3& light_radiance, float light_size) {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2, 0, -2), glm::vec3(2, 3, 2));
  const int mirror = test::add_material(scene, test::make_material(glm::vec3(1.0f), 0.0f, 1.0f, "mirror"));
  const int metal = test::add_material(scene, test::make_material(glm::vec3(1.0f), 1e-4f, 1.0f, "metal"));
  scenes::Material glass_m = test::make_material(glm::vec3(1.0f), 0.0f, 0.0f, "glass");
  glass_m.transmission_factor = 1.0f;
  const int glass = test::add_material(scene, glass_m);
  const int light = test::add_material(scene, test::make_emitter(light_radiance, true));
  test::add_quad(scene, glm::vec3(-1.9f, 0.2f, -1.99f), glm::vec3(3.8f, 0, 0), glm::vec3(0, 2.6f, 0), mirror);
  test::add_uv_sphere(scene, glm::vec3(0.7f, 0.6f, 0.5f), 0.5f, metal, 24, 12);
  test::add_uv_sphere(scene, glm::vec3(-0.7f, 0.6f, 0.5f), 0.5f, glass, 24, 12);
  test::add_quad(scene, glm::vec3(0, 2.5f, 0), glm::vec3(light_size, 0, 0), glm::vec3(0, 0, light_size), light);
  return scene;
}

TEST(Stress, MirrorsMetalsAndGlassUnderATinyVeryBrightLight) {
  // 1 mm^2 at 1e8: the power of an ordinary panel from a millionth of its area.
  const scenes::Scene scene = hard_room(glm::vec3(1e8f), 1e-3f);
  const RenderScene rs(scene);
  expect_all_finite(render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), settings(16)));
}

TEST(Stress, HugeEmitterRadianceStaysFinite) {
  const scenes::Scene scene = hard_room(glm::vec3(1e20f), 0.5f);
  const RenderScene rs(scene);
  expect_all_finite(render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), settings(4)));
}

TEST(Stress, GrazingViewsAlongTheFloorAndACameraOnASurface) {
  const scenes::Scene scene = hard_room(glm::vec3(20.0f), 0.5f);
  const RenderScene rs(scene);
  // 0.1 mm above the floor every view of it is grazing; on the wall itself half the
  // sphere of directions is behind the surface.
  expect_all_finite(render_view(rs, panorama(glm::vec3(0.3f, 1e-4f, -0.4f)), settings(8)));
  expect_all_finite(render_view(rs, panorama(glm::vec3(-2.0f, 1.0f, 0.0f)), settings(8)));
}

TEST(Stress, DegenerateTrianglesDoNotPoisonTheImage) {
  scenes::Scene scene = hard_room(glm::vec3(20.0f), 0.5f);
  scenes::Mesh bad;
  bad.name = "degenerate";
  bad.material = 0;
  // Zero area (repeated vertex), collinear, a sliver 1e-12 wide, and a needle.
  bad.positions = {{0, 1, 0}, {0, 1, 0}, {0.5f, 1, 0}, {0, 1.2f, 0}, {0.5f, 1.2f, 0}, {1, 1.2f, 0},
                   {0, 1.4f, 0}, {1, 1.4f, 0}, {0.5f, 1.4f, 1e-12f}, {0, 1.6f, 0}, {1e-7f, 1.6f, 0}, {0, 1.6f + 1e-7f, 0}};
  bad.normals.assign(bad.positions.size(), glm::vec3(0.0f));  // zero normals: unusable
  bad.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}};
  test::add_mesh(scene, bad);
  const RenderScene rs(scene);
  expect_all_finite(render_view(rs, panorama(glm::vec3(0.2f, 1.3f, 0.3f)), settings(8)));
}

TEST(Stress, ZeroAndOneParametersEverywhere) {
  for (float base : {0.0f, 1.0f})
    for (float roughness : {0.0f, 1e-6f, 1.0f})
      for (float metalness : {0.0f, 1.0f}) {
        scenes::Scene scene = test::make_box_room(glm::vec3(-1), glm::vec3(1), test::make_material(glm::vec3(base), roughness, metalness));
        const int light = test::add_material(scene, test::make_emitter(glm::vec3(5.0f)));
        test::add_quad(scene, glm::vec3(-0.2f, 0.99f, -0.2f), glm::vec3(0.4f, 0, 0), glm::vec3(0, 0, 0.4f), light);
        const RenderScene rs(scene);
        SCOPED_TRACE(testing::Message() << "B=" << base << " R=" << roughness << " M=" << metalness);
        expect_all_finite(render_view(rs, panorama(glm::vec3(0.1f, 0.2f, -0.3f)), settings(4)));
      }
}

}  // namespace
}  // namespace phyir::render
