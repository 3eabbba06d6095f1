// Texture filtering at camera hits: the mip pyramid (OpenImageIO box halving) holds the
// means of the texels below, trilinear lookups blend two levels, and a distant checkerboard
// seen through a panorama's pixels reads as the pixels' mean colour (what a supersampled
// render converges to) instead of aliasing to black or white; a later ray of the path, which
// starts as wide as the footprint it leaves, reads what the camera ray's cone would have read
// there. Rays without a cone (probe texels, shadow rays: spread and width 0) read the full
// resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "phyir/render/camera.h"
#include "phyir/render/render_scene.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

scenes::Texture ramp_texture(int width, int height) {
  std::vector<glm::vec4> texels;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) texels.push_back(glm::vec4(float(x), float(y), float(x * y), 1.0f));
  return scenes::Texture::from_linear(width, height, texels);  // float: the means are exact
}

TEST(TextureMips, EachLevelHoldsTheMeansOfTheTexelsBelow) {
  scenes::Texture t = ramp_texture(8, 4);
  t.build_mips();
  ASSERT_EQ(t.levels(), 4);  // 8x4, 4x2, 2x1, 1x1
  EXPECT_EQ(t.level_width(1), 4);
  EXPECT_EQ(t.level_height(1), 2);
  EXPECT_EQ(t.level_width(3), 1);
  EXPECT_EQ(t.level_height(3), 1);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      glm::vec4 mean(0.0f);
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) mean += t.texel(2 * x + dx, 2 * y + dy) / 4.0f;
      const glm::vec4 level1 = t.texel(x, y, 1);
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(level1[c], mean[c], 1e-5f) << x << "," << y;
    }
  // The 1x1 top is the mean of everything: x 3.5, y 1.5, xy 5.25.
  EXPECT_NEAR(t.texel(0, 0, 3).x, 3.5f, 1e-4f);
  EXPECT_NEAR(t.texel(0, 0, 3).y, 1.5f, 1e-4f);
  EXPECT_NEAR(t.texel(0, 0, 3).z, 5.25f, 1e-4f);
  scenes::Texture odd = ramp_texture(5, 3);
  odd.build_mips();
  EXPECT_EQ(odd.levels(), 4);  // 5x3, 3x2, 2x1, 1x1
  EXPECT_EQ(odd.level_width(1), 3);
}

TEST(TextureMips, LookupsBlendTheTwoLevelsAroundTheLod) {
  scenes::Texture t = ramp_texture(8, 8);
  t.build_mips();
  const glm::vec2 uv(0.3f, 0.6f);
  EXPECT_EQ(t.sample(uv, 0.0f), t.sample(uv));
  EXPECT_EQ(t.sample(uv, -2.0f), t.sample(uv));
  const glm::vec4 one = t.sample(uv, 1.0f), two = t.sample(uv, 2.0f), between = t.sample(uv, 1.25f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(between[c], 0.75f * one[c] + 0.25f * two[c], 1e-5f);
  EXPECT_EQ(t.sample(uv, 99.0f), t.sample(uv, float(t.levels() - 1)));  // clamped to the 1x1 top
  scenes::Texture plain = ramp_texture(8, 8);
  EXPECT_EQ(plain.sample(uv, 3.0f), plain.sample(uv));  // no pyramid: full resolution
}

// A floor (y = 0) covered by a 512 x 512 checkerboard of `cell` x `cell` texel squares (single
// texels by default) repeated every 0.5 m, seen from 1.5 m above through a 128 x 64 panorama:
// far away, each pixel spans hundreds of texels. Mip levels above log2(cell) are uniform 0.5.
struct CheckerFloor {
  scenes::Scene scene;
  CameraModel camera;
  explicit CheckerFloor(int cell = 1) {
    std::vector<glm::vec4> texels;
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 512; ++x) texels.push_back(glm::vec4(glm::vec3(float((x / cell + y / cell) % 2)), 1.0f));
    scenes::Texture checker = scenes::Texture::from_linear(512, 512, texels);
    checker.build_mips();
    scene.textures.push_back(std::move(checker));
    scenes::Material m = test::make_material(glm::vec3(1.0f));
    m.base_color_texture.texture = 0;
    const int material = test::add_material(scene, m);
    scenes::Mesh floor;
    floor.material = material;
    test::append_quad(floor, glm::vec3(-40, 0, 40), glm::vec3(80, 0, 0), glm::vec3(0, 0, -80));
    for (glm::vec2& uv : floor.texcoords0) uv *= 160.0f;  // 0.5 m per repeat
    test::add_mesh(scene, std::move(floor));
    camera.projection = Projection::Equirectangular;
    camera.position = glm::vec3(0.0f, 1.5f, 0.0f);
    camera.width = 128;
    camera.height = 64;
  }
};

float base_colour(const RenderScene& rs, Ray ray, bool filtered) {
  if (!filtered) ray.spread = 0.0f;
  SurfaceInteraction si;
  return rs.trace(ray, &si) ? si.brdf.base_color.x : -1.0f;
}

TEST(TextureFootprint, ADistantCheckerboardReadsAsThePixelsMeanNotAsAliases) {
  const CheckerFloor f;
  const RenderScene rs(f.scene);
  double filtered_error2 = 0.0, point_error2 = 0.0, filtered_sum = 0.0, reference_sum = 0.0;
  int pixels = 0;
  for (int y = 33; y < 48; ++y) {  // below the horizon down to ~40 degrees: the floor 1.5-30 m away
    for (int x = 0; x < 128; x += 3) {
      // Reference: the pixel's mean over 16 x 16 sub-pixel rays at full resolution.
      double reference = 0.0;
      for (int sy = 0; sy < 16; ++sy)
        for (int sx = 0; sx < 16; ++sx)
          reference += base_colour(rs, f.camera.generate_ray(glm::vec2(x + (sx + 0.5f) / 16, y + (sy + 0.5f) / 16)), false);
      reference /= 256.0;
      const Ray centre = f.camera.generate_ray(glm::vec2(x + 0.5f, y + 0.5f));
      const double filtered = base_colour(rs, centre, true), point = base_colour(rs, centre, false);
      ASSERT_GE(filtered, 0.0);
      filtered_error2 += (filtered - reference) * (filtered - reference);
      point_error2 += (point - reference) * (point - reference);
      filtered_sum += filtered;
      reference_sum += reference;
      ++pixels;
    }
  }
  const double filtered_rmse = std::sqrt(filtered_error2 / pixels), point_rmse = std::sqrt(point_error2 / pixels);
  std::printf("[ checker floor ] %d pixels: RMSE against the 256-ray pixel mean: point-sampled %.3f, filtered %.3f; "
              "mean filtered %.3f, reference %.3f\n", pixels, point_rmse, filtered_rmse, filtered_sum / pixels,
              reference_sum / pixels);
  EXPECT_LT(filtered_rmse, 0.3 * point_rmse);
  EXPECT_NEAR(filtered_sum / pixels, reference_sum / pixels, 0.03);
}

// The footprint is width + spread x t: a ray that starts k metres along the camera ray's cone,
// as wide as the cone is there, reads the same texture level as the camera ray itself. Squares
// of 256 texels (0.25 m) keep levels 0-8 distinct, so a finer level reads another value.
TEST(TextureFootprint, ALaterRayContinuesTheCone) {
  const CheckerFloor f(256);
  const RenderScene rs(f.scene);
  int compared = 0;
  for (float y = 36.5f; y < 48.0f; y += 1.0f) {
    const Ray camera_ray = f.camera.generate_ray(glm::vec2(20.5f, y));
    SurfaceInteraction hit;
    ASSERT_TRUE(rs.trace(camera_ray, &hit));
    const float k = 0.6f * hit.distance;
    Ray later{camera_ray.origin + k * camera_ray.direction, camera_ray.direction};
    later.spread = camera_ray.spread;
    later.width = camera_ray.spread * k;
    const float from_camera = base_colour(rs, camera_ray, true), continued = base_colour(rs, later, true);
    EXPECT_NEAR(continued, from_camera, 1e-4f) << y;
    Ray narrow = later;
    narrow.width = 0.0f;  // the cone restarted at the later origin: a finer level
    if (std::abs(base_colour(rs, narrow, true) - from_camera) > 1e-3f) ++compared;
  }
  EXPECT_GE(compared, 6) << "the width must matter on most of the 12 pixels, or the test sees nothing";
}

TEST(TextureFootprint, NonCameraRaysAndGrazingHitsStayFinite) {
  const CheckerFloor f;
  const RenderScene rs(f.scene);
  for (float y = 32.01f; y < 34.0f; y += 0.1f) {  // just below the horizon: grazing
    const Ray ray = f.camera.generate_ray(glm::vec2(10.5f, y));
    ASSERT_GT(ray.spread, 0.0f);
    const float c = base_colour(rs, ray, true);
    if (c >= 0.0f) {
      EXPECT_TRUE(std::isfinite(c) && c <= 1.0f) << y;
    }
  }
  const Ray sharp{glm::vec3(0.0f, 1.5f, 0.0f), glm::normalize(glm::vec3(0.1f, -1.0f, 0.0f))};
  const float c = base_colour(rs, sharp, true);
  EXPECT_TRUE(c == 0.0f || c == 1.0f || (c > 0.0f && c < 1.0f));  // a bilinear level-0 value
}

}  // namespace
}  // namespace phyir::render
