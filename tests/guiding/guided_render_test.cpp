// Path guiding in the path tracer (render/guided_render.h, guide_mixture.h): the pass schedule
// spends exactly the budget, a guided image is the same for any thread count, it converges to
// the unguided image's value (a room of glowing walls, and a room lit by a small lamp),
// and render stats say what the guide learned.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numeric>

#include "phyir/core/safe_math.h"
#include "phyir/core/setting_error.h"
#include "phyir/render/render_view.h"
#include "render/test_scenes.h"

namespace phyir::render {
namespace {

CameraModel panorama(const glm::vec3& position) {
  CameraModel c;
  c.position = position;
  c.width = 64;
  c.height = 32;
  return c;
}

RenderSettings settings(int spp, bool guiding) {
  RenderSettings s;
  s.spp = spp;
  s.seed = 5;
  s.progress = false;
  s.aovs = false;
  s.guiding.enabled = guiding;
  s.guiding.tree.spatial_threshold = 2000.0;  // a 64x32 image: split at all
  return s;
}

double mean_luminance(const Image& image) {
  double sum = 0.0;
  const size_t n = size_t(image.width) * image.height, c = size_t(image.channels);
  for (size_t i = 0; i < n; ++i)
    sum += luminance(glm::vec3(image.pixels[c * i], image.pixels[c * i + 1], image.pixels[c * i + 2]));
  return sum / double(n);
}

// A closed room of grey walls (base colour 0.5, rough) that all emit radiance 1: light is
// everywhere, every path is lit at every vertex, and the image is nearly flat (about 2). Next-event
// estimation, the hit's MIS weight and the mixture all act on every vertex.
scenes::Scene furnace_room() {
  scenes::Material wall = test::make_material(glm::vec3(0.5f), 1.0f, 0.0f, "wall");
  wall.emissive_factor = glm::vec3(1.0f);
  return test::make_box_room(glm::vec3(-2, 0, -1.5f), glm::vec3(2, 2.5f, 1.5f), wall);
}

// A room of grey walls lit by a small bright lamp in a corner of the ceiling, with a glossy
// floor: the light the guide should find.
scenes::Scene lamp_room() {
  scenes::Scene scene = test::make_box_room(glm::vec3(-2, 0, -1.5f), glm::vec3(2, 2.5f, 1.5f),
                                            test::make_material(glm::vec3(0.6f), 0.9f));
  const int lamp = test::add_material(scene, test::make_emitter(glm::vec3(200.0f)));
  test::add_quad(scene, glm::vec3(1.5f, 2.49f, 1.0f), glm::vec3(0.2f, 0, 0), glm::vec3(0, 0, 0.2f), lamp, "lamp");
  const int floor_material = test::add_material(scene, test::make_material(glm::vec3(0.7f), 0.3f, 0.0f, "glossy"));
  test::add_quad(scene, glm::vec3(-1.0f, 0.01f, -1.0f), glm::vec3(0, 0, 2), glm::vec3(2, 0, 0), floor_material, "rug");
  return scene;
}

TEST(GuidingPasses, DoublingPassesSpendExactlyTheBudget) {
  for (int spp : {1, 2, 3, 4, 7, 16, 100, 256, 1000}) {
    const std::vector<int> passes = guiding_passes(spp);
    EXPECT_EQ(std::accumulate(passes.begin(), passes.end(), 0), spp) << spp;
    for (size_t k = 0; k + 1 < passes.size(); ++k) EXPECT_EQ(passes[k], 1 << k) << spp;
    if (passes.size() > 1) {
      EXPECT_GE(passes.back(), 2 * passes[passes.size() - 2]) << spp;
    }
  }
  EXPECT_EQ(guiding_passes(256), (std::vector<int>{1, 2, 4, 8, 16, 32, 64, 129}));
  EXPECT_EQ(guiding_passes(1), std::vector<int>{1});
}

TEST(GuidedRender, SameSeedSameImageWhateverTheThreadCount) {
  const scenes::Scene scene = lamp_room();
  const RenderScene rs(scene);
  Image one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = render_view(rs, panorama(glm::vec3(0, 1.2f, 0)), settings(16, true)).film.color();
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = render_view(rs, panorama(glm::vec3(0, 1.2f, 0)), settings(16, true)).film.color();
  }
  EXPECT_EQ(one.pixels, two.pixels);
}

TEST(GuidedRender, FurnaceAgreesWithTheUnguidedImage) {
  const scenes::Scene scene = furnace_room();
  const RenderScene rs(scene);
  const CameraModel camera = panorama(glm::vec3(0, 1.2f, 0));
  const RenderOutput guided = render_view(rs, camera, settings(32, true));
  ASSERT_TRUE(guided.stats.guiding.ran);
  EXPECT_GT(guided.stats.guiding.tree.passes, 2u);
  const double plain = mean_luminance(render_view(rs, camera, settings(32, false)).film.color());
  // Both image means carry ~0.1% noise here; a weight off by the mixture is off by far more.
  EXPECT_NEAR(mean_luminance(guided.film.color()), plain, 0.005 * plain);
}

TEST(GuidedRender, ConvergesToTheUnguidedImage) {
  const scenes::Scene scene = lamp_room();
  const RenderScene rs(scene);
  const CameraModel camera = panorama(glm::vec3(0, 1.2f, 0));
  const RenderOutput guided = render_view(rs, camera, settings(128, true));
  const RenderOutput plain = render_view(rs, camera, settings(128, false));
  const double g = mean_luminance(guided.film.color()), p = mean_luminance(plain.film.color());
  // Both are unbiased: the image means agree to their noise (about 1% here); a wrong weight
  // (the BRDF's density in place of the mixture's) is off by tens of percent.
  EXPECT_NEAR(g, p, 0.03 * p);
  EXPECT_EQ(guided.stats.counters.nonfinite_samples, 0u);
  // The guide learned something: the room split, records kept, none rejected.
  const guiding::SDTreeStats& tree = guided.stats.guiding.tree;
  EXPECT_GT(tree.spatial_leaves, 1u);
  EXPECT_GT(tree.records, 0u);
  EXPECT_EQ(tree.rejected_records, 0u);
  EXPECT_FALSE(plain.stats.guiding.ran);
}

TEST(GuidedRender, BadSettingsAreNamed) {
  const scenes::Scene scene = lamp_room();
  const RenderScene rs(scene);
  RenderSettings s = settings(4, true);
  s.guiding.bsdf_fraction = 0.0f;  // the guide alone could miss directions the BRDF reaches
  EXPECT_THROW(render_view(rs, panorama(glm::vec3(0, 1.2f, 0)), s), SettingError);
}

}  // namespace
}  // namespace phyir::render
