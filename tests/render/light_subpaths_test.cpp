// Light subpaths (light_subpaths.h, docs/light-subpaths.md) against what they must satisfy:
// the emitter sampler's stated probability of choosing a punctual light is the one its
// samples carry; the light strategy's density of a point integrates to one over a closed
// room (every subpath lands somewhere); and the path tracer's estimate is the same with and
// without them (their weights sum to one), with less variance where a bulb sits a few
// centimetres under the ceiling it lights.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "phyir/core/safe_math.h"
#include "phyir/render/emitter_sampler.h"
#include "phyir/render/light_subpaths.h"
#include "phyir/render/path_tracer.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "phyir/render/streams.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

const glm::vec3 kRoomMin(-1.5f, 0.0f, -2.0f), kRoomMax(1.5f, 2.5f, 2.0f);

// A 3 x 2.5 x 4 m room of white walls with a point light `below_ceiling` under its
// ceiling, plus, where asked, a spot light on a wall and an emissive panel.
scenes::Scene room(float below_ceiling, bool more_lights) {
  scenes::Scene scene = test::make_box_room(kRoomMin, kRoomMax, test::make_material(glm::vec3(0.7f)));
  scene.lights.push_back(test::make_point_light(20.0f, glm::vec3(0.3f, kRoomMax.y - below_ceiling, 0.5f)));
  if (!more_lights) return scene;
  scene.lights.push_back(test::make_punctual_light(scenes::PunctualLight::Type::Spot, 10.0f,
                                                   glm::vec3(-1.0f, 1.5f, 1.0f), glm::vec3(1.0f, -0.5f, -1.0f), 0.3f,
                                                   0.6f));
  test::add_quad(scene, glm::vec3(1.4f, 1.0f, -1.0f), glm::vec3(0, 0, 0.5f), glm::vec3(0, 0.5f, 0),
                 test::add_material(scene, test::make_emitter(glm::vec3(3.0f))), "panel");
  return scene;
}

TEST(EmitterSamplerDeltaPmf, IsThePdfItsPunctualSamplesCarry) {
  const scenes::Scene scene = room(0.3f, true);
  const RenderScene rs(scene);
  Rng rng(7, 1);
  int delta_samples = 0;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 reference = glm::mix(kRoomMin, kRoomMax, glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()));
    EmitterSample ls;
    if (!rs.emitters().sample(reference, rng.next_float(), rng.next_2d(), &ls) || !ls.delta) continue;
    ++delta_samples;
    EXPECT_FLOAT_EQ(ls.pdf, rs.emitters().delta_pmf(reference, ls.light)) << "light " << ls.light;
  }
  EXPECT_GT(delta_samples, 200);
}

// The integral of density() over the room's six walls (uniform points on each, normals
// facing in), summed over the lights: the probability that a subpath lands at all, 1.
double density_integral(const scenes::Scene& scene, int side) {
  const RenderScene rs(scene);
  const LightSubpaths subpaths(rs);
  const glm::vec3 x(0.2f, 0.9f, -0.4f), d = kRoomMax - kRoomMin;
  struct Wall {
    glm::vec3 corner, u, v, normal;
  };
  const Wall walls[6] = {{kRoomMin, {0, d.y, 0}, {0, 0, d.z}, {1, 0, 0}},
                         {kRoomMin + glm::vec3(d.x, 0, 0), {0, d.y, 0}, {0, 0, d.z}, {-1, 0, 0}},
                         {kRoomMin, {d.x, 0, 0}, {0, 0, d.z}, {0, 1, 0}},
                         {kRoomMin + glm::vec3(0, d.y, 0), {d.x, 0, 0}, {0, 0, d.z}, {0, -1, 0}},
                         {kRoomMin, {d.x, 0, 0}, {0, d.y, 0}, {0, 0, 1}},
                         {kRoomMin + glm::vec3(0, 0, d.z), {d.x, 0, 0}, {0, d.y, 0}, {0, 0, -1}}};
  double total = 0.0;
  Rng rng(3, 1);
  for (const Wall& w : walls) {
    const double area = double(glm::length(glm::cross(w.u, w.v)));
    double sum = 0.0;
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b) {
        const glm::vec3 y = w.corner + w.u * ((float(a) + rng.next_float()) / float(side)) +
                            w.v * ((float(b) + rng.next_float()) / float(side));
        for (int light = 0; light < int(scene.lights.size()); ++light)
          sum += double(subpaths.density(x, light, y, w.normal));
      }
    total += area * sum / double(side * side);
  }
  return total;
}

TEST(LightSubpathsDensity, IntegratesToOneOverAClosedRoom) {
  const double total = density_integral(room(0.05f, true), 600);
  std::printf("[ density ] integral over the room %.4f\n", total);
  EXPECT_NEAR(total, 1.0, 0.01);
}

// Beyond 64 lights the choice is by power alone: still a density of total 1.
TEST(LightSubpathsDensity, IntegratesToOneWithManyLightsChosenByPower) {
  scenes::Scene scene = room(0.05f, false);
  Rng rng(9, 1);
  for (int i = 0; i < 70; ++i)
    scene.lights.push_back(test::make_point_light(
        1.0f + 10.0f * rng.next_float(),
        glm::mix(kRoomMin + glm::vec3(0.1f), kRoomMax - glm::vec3(0.1f), glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()))));
  const double total = density_integral(scene, 150);
  std::printf("[ density ] 71 lights: integral over the room %.4f\n", total);
  EXPECT_NEAR(total, 1.0, 0.02);
}

struct Estimate {
  double mean = 0.0, standard_error = 0.0;
};

// n paths along `ray`: mean luminance and its standard error.
Estimate paths(const RenderScene& rs, bool light_subpaths, const Ray& ray, int n) {
  PathSettings settings;
  settings.light_subpaths = light_subpaths;
  const PathTracer tracer(rs, analyse_effects(rs.scene(), false), settings);
  PathCounters counters;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double l = luminance(tracer.radiance(ray, sample_key(11, 0, uint64_t(i)), &counters));
    sum += l;
    sum2 += l * l;
  }
  EXPECT_EQ(counters.nonfinite_samples, 0u);
  Estimate e;
  e.mean = sum / n;
  e.standard_error = std::sqrt(std::max(0.0, sum2 / n - e.mean * e.mean) / n);
  return e;
}

// A ray from the room's middle down to the floor: the floor's indirect light, which the
// ceiling round the bulb dominates.
const Ray kToTheFloor{glm::vec3(-0.4f, 1.2f, -0.8f), glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f))};

TEST(LightSubpathsPathTracer, TheEstimateIsTheSameWithAndWithoutThem) {
  scenes::Scene scene = room(0.25f, true);
  // A glossy floor: the eye strategy's density of a subpath's point is the BRDF's there.
  scene.meshes[2].material = test::add_material(scene, test::make_material(glm::vec3(0.8f, 0.6f, 0.4f), 0.35f, 0.5f));
  const RenderScene rs(scene);
  const Estimate without = paths(rs, false, kToTheFloor, 200000), with = paths(rs, true, kToTheFloor, 100000);
  const double sigma = std::hypot(without.standard_error, with.standard_error);
  std::printf("[ unbiased ] without %.5f +- %.5f, with %.5f +- %.5f\n", without.mean, without.standard_error, with.mean,
              with.standard_error);
  ASSERT_GT(without.mean, 0.0);
  EXPECT_LT(std::abs(with.mean - without.mean), 4.0 * sigma);
}

TEST(LightSubpathsPathTracer, ABulbUnderTheCeilingLeavesLessNoise) {
  const scenes::Scene scene = room(0.03f, false);
  const RenderScene rs(scene);
  const Estimate without = paths(rs, false, kToTheFloor, 40000), with = paths(rs, true, kToTheFloor, 40000);
  const double ratio = (without.standard_error * without.standard_error) / (with.standard_error * with.standard_error);
  std::printf("[ near field ] variance without / with %.2f (means %.5f, %.5f)\n", ratio, without.mean, with.mean);
  EXPECT_GT(ratio, 2.0);
}

}  // namespace
}  // namespace phyir::render
