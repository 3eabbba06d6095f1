// Emissive faces that light only the inside of closed geometry (a fixture's diffuser
// pressed against its housing) are left out of light sampling: found exactly, and the
// irradiance estimate keeps its mean while far fewer of its samples are wasted.
#include "phyir/render/emitter_visibility.h"

#include <gtest/gtest.h>

#include <cmath>

#include "phyir/core/safe_math.h"
#include "phyir/render/emitter_sampler.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

// The generator's ceiling light: a 0.6 m housing 1 mm under a 2.6 m ceiling, and under it a
// 2 mm diffuser box whose top face lies in the housing's bottom face.
scenes::Scene fixture_room() {
  scenes::Scene scene = test::make_box_room({-2, 0, -2}, {2, 2.6f, 2});
  const int housing = test::add_material(scene, test::make_material(glm::vec3(0.8f)));
  const int diffuser = test::add_material(scene, test::make_emitter(glm::vec3(20.0f)));
  test::add_box(scene, {-0.3f, 2.569f, -0.3f}, {0.3f, 2.599f, 0.3f}, housing, false, "housing");
  test::add_box(scene, {-0.3f, 2.567f, -0.3f}, {0.3f, 2.569f, 0.3f}, diffuser, false, "diffuser");
  return scene;
}

TEST(EmitterVisibility, TheDiffuserTopInsideTheHousingIsLeftOutAndNothingElse) {
  const scenes::Scene scene = fixture_room();
  const RenderScene render_scene(scene);
  EXPECT_EQ(render_scene.emitters().enclosed_triangle_count(), 2u);  // the top face's two triangles
  EXPECT_EQ(render_scene.emitters().emissive_triangle_count(), 10u);

  // The same diffuser hanging free: every face lights the room.
  scenes::Scene free_hanging = test::make_box_room({-2, 0, -2}, {2, 2.6f, 2});
  const int diffuser = test::add_material(free_hanging, test::make_emitter(glm::vec3(20.0f)));
  test::add_box(free_hanging, {-0.3f, 2.0f, -0.3f}, {0.3f, 2.002f, 0.3f}, diffuser, false, "diffuser");
  const RenderScene free_scene(free_hanging);
  EXPECT_EQ(free_scene.emitters().enclosed_triangle_count(), 0u);
  EXPECT_EQ(free_scene.emitters().emissive_triangle_count(), 12u);
}

TEST(EmitterVisibility, ATwoSidedFaceIsEnclosedOnlyWhenBothSidesAre) {
  scenes::Scene scene = test::make_box_room({-2, 0, -2}, {2, 2.6f, 2});
  const int solid = test::add_material(scene, test::make_material(glm::vec3(0.5f)));
  const int glow = test::add_material(scene, test::make_emitter(glm::vec3(5.0f), /*double_sided=*/true));
  // A two-sided emissive card on top of a closed block: its underside faces into the
  // block, its upper side faces the room.
  test::add_box(scene, {-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, solid, false, "block");
  test::add_quad(scene, {-0.2f, 0.999f, -0.2f}, {0, 0, 0.4f}, {0.4f, 0, 0}, glow, "card");
  const RenderScene render_scene(scene);
  EXPECT_EQ(render_scene.emitters().enclosed_triangle_count(), 0u);
}

// Direct irradiance at a ceiling point 10 cm beside the fixture, by light sampling alone:
// the sampler that leaves the enclosed face out must give the same mean (the face's light
// never arrives) with most of its samples unblocked, where the plain one wastes most.
TEST(EmitterVisibility, LeavingEnclosedFacesOutKeepsTheMeanAndStopsWastingSamples) {
  const scenes::Scene scene = fixture_room();
  const RenderScene render_scene(scene);
  const EmitterSampler plain(scene);
  const EmitterSampler& pruned = render_scene.emitters();
  const glm::vec3 x(0.4f, 2.6f - 1e-4f, 0.1f), n(0, -1, 0);
  auto estimate = [&](const EmitterSampler& sampler, double* unblocked_fraction, double* standard_error) {
    constexpr int kSamples = 200000;
    Rng rng(1234, 5);
    double sum = 0.0, sum2 = 0.0;
    int unblocked = 0;
    for (int i = 0; i < kSamples; ++i) {
      const float u = rng.next_float();
      const glm::vec2 uv = rng.next_2d();
      EmitterSample ls;
      double value = 0.0;
      if (sampler.sample(x, u, uv, &ls) && ls.pdf > 0.0f && glm::dot(ls.wi, n) > 0.0f) {
        Ray shadow{spawn_origin(x, n, ls.wi), ls.wi};
        shadow.tmax = ls.distance * (1.0f - 1e-4f);
        if (!render_scene.accelerator().occluded(shadow)) {
          ++unblocked;
          value = double(luminance(ls.radiance)) * glm::dot(ls.wi, n) / ls.pdf;
        }
      }
      sum += value;
      sum2 += value * value;
    }
    const double mean = sum / kSamples;
    *standard_error = std::sqrt(std::max(sum2 / kSamples - mean * mean, 0.0) / kSamples);
    *unblocked_fraction = double(unblocked) / kSamples;
    return mean;
  };
  double plain_unblocked = 0, pruned_unblocked = 0, plain_se = 0, pruned_se = 0;
  const double plain_mean = estimate(plain, &plain_unblocked, &plain_se);
  const double pruned_mean = estimate(pruned, &pruned_unblocked, &pruned_se);
  std::cout << "plain: E = " << plain_mean << " +- " << plain_se << ", " << plain_unblocked * 100
            << "% unblocked; pruned: E = " << pruned_mean << " +- " << pruned_se << ", " << pruned_unblocked * 100
            << "% unblocked\n";
  ASSERT_GT(pruned_mean, 0.0);
  EXPECT_NEAR(plain_mean, pruned_mean, 4.0 * std::hypot(plain_se, pruned_se));
  EXPECT_LT(plain_unblocked, 0.1);
  EXPECT_GT(pruned_unblocked, 0.9);
  EXPECT_LT(pruned_se, 0.5 * plain_se);
}

}  // namespace
}  // namespace phyir::render
