// Light portals (environment_portals.h): the sampler's density integrates to one and is what
// it samples with; the path tracer through a window is the same with and without portals,
// and less noisy with them.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "phyir/core/safe_math.h"
#include "phyir/render/effects.h"
#include "phyir/render/environment_portals.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"
#include "phyir/render/streams.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

// A window 1 m wide and high in the +X wall of a 4 x 3 x 4 m room, and a second one in the
// -Z wall, their edges crossed into the room.
std::vector<scenes::Portal> two_windows() {
  return {{glm::vec3(2.0f, 1.0f, -0.5f), glm::vec3(0, 0, 1), glm::vec3(0, 1, 0)},
          {glm::vec3(-1.0f, 1.2f, -2.0f), glm::vec3(0.8f, 0, 0), glm::vec3(0, 1, 0)}};
}

TEST(EnvironmentPortals, DensityIntegratesToOneOverTheSphere) {
  const EnvironmentPortals portals(two_windows());
  // Points that see both windows over 0.3-1 sr: 2 M uniform directions find them tens of
  // thousands of times, the integral to ~0.5%.
  for (const glm::vec3& x : {glm::vec3(0.0f, 1.5f, 0.0f), glm::vec3(1.2f, 1.4f, -1.2f), glm::vec3(-1.0f, 1.6f, 1.0f)}) {
    Rng rng(7, 1);
    const int n = 2000000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += portals.pdf(x, sample_uniform_sphere(rng.next_2d()));
    EXPECT_NEAR(sum / n * 4.0 * kPi, 1.0, 0.02) << "from " << x.x << "," << x.y << "," << x.z;
  }
}

TEST(EnvironmentPortals, SamplesGoThroughAPortalWithTheDensityItStates) {
  const EnvironmentPortals portals(two_windows());
  const glm::vec3 x(0.3f, 1.1f, 0.4f);
  Rng rng(3, 2);
  double inverse_sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    glm::vec3 d;
    float pdf = 0.0f;
    ASSERT_TRUE(portals.sample(x, glm::vec3(rng.next_2d(), rng.next_float()), &d, &pdf));
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    EXPECT_GT(pdf, 0.0f);
    EXPECT_NEAR(pdf, portals.pdf(x, d), 1e-6f * pdf);
    inverse_sum += 1.0 / pdf;
  }
  // E[1 / pdf] is the solid angle sampled: both windows (exact by 1 / pdf being constant).
  const double total = inverse_sum / n;
  EXPECT_GT(total, 0.1);
  glm::vec3 unused;
  float unused_pdf;
  // Outside, behind both windows, nothing faces the point.
  EXPECT_FALSE(portals.sample(glm::vec3(5.0f, 1.5f, -5.0f), glm::vec3(0.5f), &unused, &unused_pdf));
  EXPECT_EQ(portals.pdf(glm::vec3(0.0f, 1.5f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)), 0.0f);  // at the ceiling
}

// The room of two_windows()' first window alone: walls of grey diffuse, the +X wall cut round it.
scenes::Scene room_with_window(bool portal) {
  scenes::Scene scene;
  const int grey = test::add_material(scene, test::make_material(glm::vec3(0.5f), 1.0f));
  test::add_quad(scene, glm::vec3(-2, 0, -2), glm::vec3(0, 0, 4), glm::vec3(4, 0, 0), grey, "floor");
  test::add_quad(scene, glm::vec3(-2, 3, -2), glm::vec3(4, 0, 0), glm::vec3(0, 0, 4), grey, "ceiling");
  test::add_quad(scene, glm::vec3(-2, 0, -2), glm::vec3(0, 3, 0), glm::vec3(0, 0, 4), grey, "wall -X");
  test::add_quad(scene, glm::vec3(-2, 0, -2), glm::vec3(4, 0, 0), glm::vec3(0, 3, 0), grey, "wall -Z");
  test::add_quad(scene, glm::vec3(-2, 0, 2), glm::vec3(0, 3, 0), glm::vec3(4, 0, 0), grey, "wall +Z");
  test::add_quad(scene, glm::vec3(2, 0, -2), glm::vec3(0, 0, 4), glm::vec3(0, 1, 0), grey, "under the window");
  test::add_quad(scene, glm::vec3(2, 2, -2), glm::vec3(0, 0, 4), glm::vec3(0, 1, 0), grey, "over the window");
  test::add_quad(scene, glm::vec3(2, 1, -2), glm::vec3(0, 0, 1.5f), glm::vec3(0, 1, 0), grey, "left of the window");
  test::add_quad(scene, glm::vec3(2, 1, 0.5f), glm::vec3(0, 0, 1.5f), glm::vec3(0, 1, 0), grey, "right of the window");
  if (portal) scene.portals = {two_windows().front()};
  return scene;
}

// A sky brighter overhead than at the horizon.
std::unique_ptr<EnvironmentLight> sky() {
  Image image(32, 16, 3, 1.0f);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = 1.0f + 0.5f * float(8 - y);
  return std::make_unique<EnvironmentLight>(image);
}

struct Estimate {
  double mean = 0.0, stderr = 0.0;
};

// The luminance a camera ray sees on the floor beside the window: mean and standard error.
Estimate floor_by_the_window(bool portal) {
  const scenes::Scene scene = room_with_window(portal);
  const RenderScene rs(scene, sky());
  EXPECT_EQ(rs.portals().size(), portal ? 1u : 0u);
  const PathTracer tracer(rs, analyse_effects(scene, true), PathSettings{});
  const glm::vec3 origin(-0.5f, 1.5f, 0.0f);
  const Ray ray{origin, glm::normalize(glm::vec3(1.2f, 0.0f, 0.6f) - origin)};
  PathCounters counters;
  double sum = 0.0, sum_sq = 0.0;
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    const double l = luminance(tracer.radiance(ray, sample_key(11, 0, uint64_t(i)), &counters));
    sum += l, sum_sq += l * l;
  }
  EXPECT_EQ(counters.nonfinite_samples, 0u);
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n)};
}

TEST(EnvironmentPortals, PathTracerIsUnchangedInMeanAndLessNoisy) {
  const Estimate without = floor_by_the_window(false), with = floor_by_the_window(true);
  EXPECT_NEAR(with.mean, without.mean, 5.0 * std::hypot(with.stderr, without.stderr));
  EXPECT_LT(with.stderr, 0.7 * without.stderr) << "with " << with.stderr << ", without " << without.stderr;
}

}  // namespace
}  // namespace phyir::render
