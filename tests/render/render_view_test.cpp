// Whole-view properties: exact depth/normal AOVs of a box room, determinism across
// thread counts, AOVs never changing colour, specialised kernels equal to forced ones,
// and defined values where a pixel sees nothing.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <limits>

#include "phyir/render/equirect.h"
#include "phyir/render/render_view.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

const glm::vec3 kRoomMin(-2.0f, 0.0f, -1.5f), kRoomMax(2.0f, 3.0f, 1.5f);

CameraModel panorama(const glm::vec3& position, int width = 64, int height = 32) {
  CameraModel c;
  c.position = position;
  c.width = width;
  c.height = height;
  return c;
}

RenderSettings quick(int spp) {
  RenderSettings s;
  s.spp = spp;
  s.seed = 42;
  s.progress = false;
  return s;
}

scenes::Scene lit_room() {
  scenes::Scene scene = test::make_box_room(kRoomMin, kRoomMax);
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(10.0f)));
  test::add_quad(scene, glm::vec3(-0.3f, 2.95f, -0.3f), glm::vec3(0, 0, 0.6f), glm::vec3(0.6f, 0, 0), light, "light");
  const int metal = test::add_material(scene, test::make_material(glm::vec3(0.9f, 0.6f, 0.3f), 0.2f, 1.0f));
  test::add_uv_sphere(scene, glm::vec3(0.8f, 0.5f, 0.4f), 0.4f, metal, 24, 12);
  return scene;
}

TEST(RenderView, DepthAndNormalOfABoxRoomAreExact) {
  const scenes::Scene scene = test::make_box_room(kRoomMin, kRoomMax);
  const RenderScene rs(scene);
  const glm::vec3 eye(0.3f, 1.4f, -0.2f);
  const RenderOutput out = render_view(rs, panorama(eye), quick(1));
  const Image& depth = out.film.aov("depth");
  const Image& normal = out.film.aov("normal");
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 64; ++x) {
      const glm::vec3 d = equirect_direction(glm::vec2((x + 0.5f) / 64, (y + 0.5f) / 32));
      // Exit distance from inside an axis-aligned box: the nearest slab along d.
      float t = std::numeric_limits<float>::infinity();
      int axis = -1;
      for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) continue;
        const float ta = ((d[a] > 0 ? kRoomMax[a] : kRoomMin[a]) - eye[a]) / d[a];
        if (ta < t) {
          t = ta;
          axis = a;
        }
      }
      ASSERT_NEAR(depth.at(x, y), t, 1e-4f * t) << x << "," << y;
      glm::vec3 expected(0.0f);
      expected[axis] = d[axis] > 0 ? -1.0f : 1.0f;  // walls face into the room
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(normal.at(x, y, c), expected[c], 1e-5f) << x << "," << y;
      ASSERT_EQ(out.film.aov("mask_geometry").at(x, y), 1.0f);
    }
  }
}

TEST(RenderView, PixelsThatSeeNothingGetZerosAndAMask) {
  scenes::Scene scene;
  const int m = test::add_material(scene, test::make_material());
  test::add_quad(scene, glm::vec3(-1, -1, -2), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0), m);  // one wall ahead
  const RenderScene rs(scene);
  const RenderOutput out = render_view(rs, panorama(glm::vec3(0)), quick(2));
  int empty = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      for (const std::string& name : Film::aov_names()) {
        const Image& aov = out.film.aov(name);
        for (int c = 0; c < aov.channels; ++c) ASSERT_TRUE(std::isfinite(aov.at(x, y, c)));
      }
      if (out.film.aov("mask_geometry").at(x, y) == 0.0f) {
        ++empty;
        EXPECT_EQ(out.film.aov("depth").at(x, y), 0.0f);
        EXPECT_EQ(out.film.aov("normal").at(x, y, 1), 0.0f);
        EXPECT_EQ(out.film.color().at(x, y, 0), 0.0f);
      }
    }
  EXPECT_GT(empty, 64 * 32 / 2);
}

TEST(RenderView, SameSeedSameImageWhateverTheThreadCount) {
  const scenes::Scene scene = lit_room();
  const RenderScene rs(scene);
  Image one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), quick(4)).film.color();
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), quick(4)).film.color();
  }
  EXPECT_EQ(one.pixels, two.pixels);
  RenderSettings other = quick(4);
  other.seed = 43;
  EXPECT_NE(render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), other).film.color().pixels, one.pixels);
}

TEST(RenderView, AovsNeverChangeColour) {
  const scenes::Scene scene = lit_room();
  const RenderScene rs(scene);
  RenderSettings with = quick(4), without = quick(4);
  without.aovs = false;
  EXPECT_EQ(render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), with).film.color().pixels,
            render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), without).film.color().pixels);
}

TEST(RenderView, SpecialisedKernelEqualsEveryEffectForcedOn) {
  const scenes::Scene scene = lit_room();
  const RenderScene rs(scene);
  RenderSettings forced = quick(4);
  forced.force_all_effects = true;
  const RenderOutput a = render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), quick(4));
  const RenderOutput b = render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), forced);
  EXPECT_FALSE(a.effects.transmission);
  EXPECT_TRUE(b.effects.transmission);
  EXPECT_EQ(a.film.color().pixels, b.film.color().pixels);
}

TEST(RenderView, PerspectiveCentreRayLooksForward) {
  CameraModel c;
  c.projection = Projection::Perspective;
  c.forward = glm::normalize(glm::vec3(1, 0, -1));
  c.width = 40;
  c.height = 20;
  const Ray r = c.generate_ray(glm::vec2(20, 10));
  EXPECT_NEAR(glm::dot(r.direction, c.forward), 1.0f, 1e-6f);
  glm::vec2 back;
  ASSERT_TRUE(c.project(c.generate_ray(glm::vec2(3.5f, 17.25f)).direction, &back));
  EXPECT_NEAR(back.x, 3.5f, 1e-3f);
  EXPECT_NEAR(back.y, 17.25f, 1e-3f);
}

TEST(RenderView, NoNonFiniteSamplesInALitRoom) {
  const scenes::Scene scene = lit_room();
  const RenderScene rs(scene);
  const RenderOutput out = render_view(rs, panorama(glm::vec3(0, 1.5f, 0)), quick(8));
  EXPECT_EQ(out.stats.counters.nonfinite_samples, 0u);
  for (float v : out.film.color().pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
}

}  // namespace
}  // namespace phyir::render
