// Rendering selected pixels gives exactly the full render's values there, for any thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "insert_test_view.h"
#include "phyir/core/error.h"
#include "phyir/insert/local_scene.h"
#include "phyir/insert/pixel_render.h"
#include "phyir/render/camera.h"

namespace phyir::insert {
namespace {

using namespace testing;

// A box on a disc under a two-tone environment, seen from 1 m up by a 64 x 32 panorama.
struct SmallScene {
  scenes::Scene scene;
  render::CameraModel camera;
  Image environment{8, 4, 3};
  SmallScene() {
    SurfacePoint ground;
    ground.position = glm::vec3(0.0f, 0.0f, -1.0f);
    scene = merge_scenes(support_disc(ground, 0.4f), place_object(box_object(0.1f), ground, Placement{}));
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 8; ++x)
        for (int c = 0; c < 3; ++c) environment.at(x, y, c) = y < 2 ? 2.0f + 0.3f * float(c) : 0.2f;
    InsertView v;
    v.color = Image(64, 32, 3);
    v.camera = kCamera;
    camera = panorama_camera(v);
  }
};

TEST(PixelRender, SelectedPixelsEqualTheFullRenderBitForBit) {
  const SmallScene s;
  const render::RenderScene rs(s.scene, std::make_unique<render::EnvironmentLight>(s.environment));
  render::RenderSettings settings;
  settings.spp = 8;
  settings.seed = 3;
  settings.progress = false;
  const render::RenderOutput full = render::render_view(rs, s.camera, settings);
  const std::vector<glm::ivec2> pixels = dilated_pixels(full.film.aov("mask_geometry"), 1);
  ASSERT_GT(pixels.size(), 20u);
  ASSERT_LT(pixels.size(), size_t(64 * 32));
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    Image color(64, 32, 3, -1.0f);
    render_pixels(rs, s.camera, settings, pixels, color);
    int set = 0;
    for (const glm::ivec2& p : pixels)
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(color.at(p.x, p.y, c), full.film.color().at(p.x, p.y, c)) << p.x << "," << p.y;
        set += color.at(p.x, p.y, c) != -1.0f;
      }
    EXPECT_EQ(set, int(3 * pixels.size()));
    EXPECT_EQ(color.at(0, 0, 0), -1.0f);  // a pixel not asked for is left alone (the zenith row)
  }
}

TEST(PixelRender, DilationWrapsColumnsAndStopsAtRows) {
  Image mask(8, 4, 1);
  mask.at(0, 0, 0) = 1.0f;
  const std::vector<glm::ivec2> p = dilated_pixels(mask, 1);
  // Columns 7, 0, 1 of rows 0 and 1.
  EXPECT_EQ(p.size(), 6u);
  EXPECT_EQ(p.front(), glm::ivec2(0, 0));
  EXPECT_EQ(p.back(), glm::ivec2(7, 1));
}

TEST(PixelRender, AnImageOfAnotherSizeIsAnError) {
  const SmallScene s;
  const render::RenderScene rs(s.scene, std::make_unique<render::EnvironmentLight>(s.environment));
  Image wrong(32, 32, 3);
  EXPECT_THROW(render_pixels(rs, s.camera, render::RenderSettings{}, {{0, 0}}, wrong), Error);
}

}  // namespace
}  // namespace phyir::insert
