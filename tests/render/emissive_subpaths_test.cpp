// Light subpaths from emissive triangles (light_subpaths.h, emissive_subpaths.cpp,
// docs/light-subpaths.md): the emitter sampler's light-side density is the one its samples
// carry and sums to one over its triangles and sides; the path tracer's estimate is the same
// with and without them (the three strategies' weights sum to one), and a glowing shade
// touching the ceiling leaves the floor's light less noisy with them.
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

// A 3 x 2.5 x 4 m room of white walls with a double-sided glowing ball (radius 10 cm, 512
// triangles) touching its ceiling and, where asked, a one-sided panel on a wall.
scenes::Scene room(bool panel) {
  scenes::Scene scene = test::make_box_room(kRoomMin, kRoomMax, test::make_material(glm::vec3(0.7f)));
  const int glowing = test::add_material(scene, test::make_emitter(glm::vec3(4.0f), true));
  test::add_uv_sphere(scene, glm::vec3(0.3f, kRoomMax.y - 0.1f, 0.5f), 0.1f, glowing, 32, 16, false, "shade");
  if (panel)
    test::add_quad(scene, glm::vec3(1.4f, 1.0f, -1.0f), glm::vec3(0, 0, 0.5f), glm::vec3(0, 0.5f, 0),
                   test::add_material(scene, test::make_emitter(glm::vec3(3.0f))), "panel");
  return scene;
}

TEST(EmitterEmission, ItsDensityIsWhatItsSamplesCarryAndSumsToOne) {
  const scenes::Scene scene = room(true);
  const RenderScene rs(scene);
  const EmitterSampler& emitters = rs.emitters();
  const glm::vec3 choice_from(-0.4f, 0.3f, 1.1f);
  // The probability of every triangle and side: 1.
  double total = 0.0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    const float sides = scene.materials[size_t(mesh.material)].double_sided ? 2.0f : 1.0f;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const glm::vec3 a = mesh.positions[mesh.triangles[t].x], b = mesh.positions[mesh.triangles[t].y],
                      c = mesh.positions[mesh.triangles[t].z];
      total += double(emitters.emission_density(choice_from, int(m), int(t))) * 0.5 *
               double(glm::length(glm::cross(b - a, c - a))) * sides;
    }
  }
  std::printf("[ emission ] total probability %.6f\n", total);
  EXPECT_NEAR(total, 1.0, 1e-4);
  Rng rng(4, 2);
  int drawn = 0;
  for (int i = 0; i < 2000; ++i) {
    EmissionVariates u;
    u.select = rng.next_float();
    u.point = rng.next_2d();
    u.side = rng.next_float();
    EmissionSample z;
    if (!emitters.sample_emission(choice_from, u, &z)) continue;
    ++drawn;
    EXPECT_FLOAT_EQ(z.density, emitters.emission_density(choice_from, z.mesh, z.triangle));
    EXPECT_GT(z.radiance.x, 0.0f);
  }
  EXPECT_GT(drawn, 1900);
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
    const double l = luminance(tracer.radiance(ray, sample_key(13, 0, uint64_t(i)), &counters));
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
// ceiling round the glowing ball dominates.
const Ray kToTheFloor{glm::vec3(-0.4f, 1.2f, -0.8f), glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f))};

TEST(EmissiveSubpathsPathTracer, TheEstimateIsTheSameWithAndWithoutThem) {
  scenes::Scene scene = room(true);
  // A glossy floor: the eye strategy's densities there are the BRDF's.
  scene.meshes[2].material = test::add_material(scene, test::make_material(glm::vec3(0.8f, 0.6f, 0.4f), 0.35f, 0.5f));
  const RenderScene rs(scene);
  const Estimate without = paths(rs, false, kToTheFloor, 200000), with = paths(rs, true, kToTheFloor, 100000);
  const double sigma = std::hypot(without.standard_error, with.standard_error);
  std::printf("[ unbiased ] without %.5f +- %.5f, with %.5f +- %.5f\n", without.mean, without.standard_error, with.mean,
              with.standard_error);
  ASSERT_GT(without.mean, 0.0);
  EXPECT_LT(std::abs(with.mean - without.mean), 4.0 * sigma);
}

TEST(EmissiveSubpathsPathTracer, AGlowingBallUnderTheCeilingLeavesLessNoise) {
  const scenes::Scene scene = room(false);
  const RenderScene rs(scene);
  const Estimate without = paths(rs, false, kToTheFloor, 40000), with = paths(rs, true, kToTheFloor, 40000);
  const double ratio = (without.standard_error * without.standard_error) / (with.standard_error * with.standard_error);
  std::printf("[ near field ] variance without / with %.2f (means %.5f, %.5f)\n", ratio, without.mean, with.mean);
  EXPECT_GT(ratio, 1.5);
}

}  // namespace
}  // namespace phyir::render
