// The emitter tree (emitter_tree.h): its pmf sums to one and equals what sample() reports
// and how often it chooses; beside a tessellated light it favours the nearest triangles,
// far away it chooses by power; and light sampling through it (emitter_sampler.h) stays
// unbiased right against a tessellated panel and a tessellated sphere lamp (against
// Lambert's formula, the part below the point's horizon clipped off).
#include "phyir/render/emitter_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "phyir/render/emitter_sampler.h"
#include "phyir/render/rng.h"
#include "monte_carlo.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

// An n x n grid of square cells (each two triangles' worth of area and power) of side `size`
// in the plane y = 0, from the origin towards +X and +Z; the cell at (i, j) has power
// `power(i, j)`.
template <typename Power>
std::vector<EmitterTree::Item> grid_items(int n, float size, Power power) {
  std::vector<EmitterTree::Item> items;
  const float cell = size / float(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      EmitterTree::Item item;
      item.lo = glm::vec3(float(i) * cell, 0.0f, float(j) * cell);
      item.hi = item.lo + glm::vec3(cell, 0.0f, cell);
      item.area = cell * cell;
      item.power = power(i, j) * item.area;
      item.normal = glm::vec3(0.0f, 1.0f, 0.0f);
      items.push_back(item);
    }
  return items;
}

const glm::vec3 kReferences[] = {{0.5f, 0.002f, 0.5f}, {0.01f, 0.001f, 0.99f}, {0.3f, 0.5f, 0.2f},
                                 {5.0f, 1.0f, -3.0f},  {0.5f, 0.0f, 0.5f},     {-100.0f, 20.0f, 40.0f}};

TEST(EmitterTree, PmfSumsToOneAndIsWhatSampleReports) {
  const auto items = grid_items(13, 1.0f, [](int i, int j) { return 1.0f + float((i * 7 + j * 3) % 5); });
  const EmitterTree tree(items);
  Rng rng(5, 9);
  for (const glm::vec3& reference : kReferences) {
    double sum = 0.0;
    for (int k = 0; k < int(items.size()); ++k) sum += tree.pmf(reference, k);
    EXPECT_NEAR(sum, 1.0, 1e-5) << reference.x << " " << reference.y << " " << reference.z;
    for (int s = 0; s < 2000; ++s) {
      float pmf = 0.0f;
      const int k = tree.sample(reference, rng.next_float(), &pmf);
      ASSERT_GE(k, 0);
      EXPECT_EQ(pmf, tree.pmf(reference, k));  // bit for bit: MIS weights compare them
    }
  }
}

TEST(EmitterTree, ChoosesAsOftenAsItsPmfSays) {
  const auto items = grid_items(4, 1.0f, [](int i, int j) { return 1.0f + float(i + 2 * j); });
  const EmitterTree tree(items);
  const glm::vec3 reference(0.1f, 0.05f, 0.8f);
  const int n = 400000;
  std::vector<int> counts(items.size(), 0);
  Rng rng(11, 2);
  for (int s = 0; s < n; ++s) {
    float pmf;
    ++counts[size_t(tree.sample(reference, rng.next_float(), &pmf))];
  }
  for (size_t k = 0; k < items.size(); ++k) {
    const double p = tree.pmf(reference, int(k));
    EXPECT_NEAR(double(counts[k]) / n, p, 4.0 * std::sqrt(p * (1.0 - p) / n) + 1e-6) << "item " << k;
  }
}

TEST(EmitterTree, BesideALightTheNearestTrianglesFarAwayThePowerShare) {
  // A 1 m panel of 32 x 32 cells of equal power, one twice as bright.
  const int n = 32;
  const auto items = grid_items(n, 1.0f, [](int i, int j) { return i == 3 && j == 29 ? 2.0f : 1.0f; });
  const EmitterTree tree(items);
  double total = 0.0;
  for (const auto& item : items) total += item.power;
  // 1 mm above the middle of cell (16, 16): that cell alone gives ~half the point's
  // irradiance, a thousandth of the power.
  const glm::vec3 above(16.5f / n, 0.001f, 16.5f / n);
  const int below = 16 * n + 16;
  const double share = items[size_t(below)].power / total;
  std::cout << "cell under a point 1 mm above: pmf " << tree.pmf(above, below) << ", power share " << share << "\n";
  EXPECT_GT(tree.pmf(above, below), 20.0 * share);
  // Far away every cell is chosen by its power share.
  const glm::vec3 far(0.5f, 1000.0f, 0.5f);
  for (int k : {0, below, 3 * n + 29})
    EXPECT_NEAR(tree.pmf(far, k), items[size_t(k)].power / total, 1e-3 * items[size_t(k)].power / total);
}

TEST(EmitterTree, ItemsWithoutPowerAreNeverChosen) {
  auto items = grid_items(3, 1.0f, [](int i, int) { return i == 1 ? 0.0f : 1.0f; });
  const EmitterTree tree(items);
  Rng rng(3, 3);
  for (int s = 0; s < 10000; ++s) {
    float pmf;
    const int k = tree.sample({0.5f, 0.001f, 0.5f}, rng.next_float(), &pmf);
    ASSERT_GE(k, 0);
    EXPECT_NE(k / 3, 1);
  }
  EXPECT_EQ(tree.pmf({0.5f, 0.001f, 0.5f}, 4), 0.0f);
  const EmitterTree none(std::vector<EmitterTree::Item>(2));
  float pmf = 1.0f;
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.sample({0, 0, 0}, 0.5f, &pmf), -1);
  EXPECT_EQ(pmf, 0.0f);
}

// Light sampling right against a tessellated panel (the ceiling beside a lamp's canopy):
// E[1 / pdf] is still the panel's solid angle, and E[cos / pdf] its irradiance factor.
TEST(EmitterTree, LightSamplingBesideATessellatedPanelIsUnbiased) {
  scenes::Scene scene;
  scenes::Mesh mesh;
  mesh.material = test::add_material(scene, test::make_emitter(glm::vec3(2.0f)));
  const int n = 16;
  const float cell = 0.5f / float(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)  // facing down (-Y) at y = 2
      test::append_quad(mesh, {float(i) * cell, 2.0f, float(j) * cell}, {cell, 0.0f, 0.0f}, {0.0f, 0.0f, cell});
  test::add_mesh(scene, std::move(mesh));
  const EmitterSampler sampler(scene);
  ASSERT_EQ(sampler.emissive_triangle_count(), size_t(2 * n * n));
  // 3 mm under the panel, near a corner: the exact solid angle of its 512 triangles.
  const glm::vec3 reference(0.02f, 1.997f, 0.03f);
  const double omega = test::mesh_solid_angle(scene.meshes[0], reference);
  Rng rng(19, 4);
  const test::MeanAndError est = test::monte_carlo(200000, [&](int) {
    EmitterSample s;
    if (!sampler.sample(reference, rng.next_float(), rng.next_2d(), &s)) return 0.0;
    return 1.0 / double(s.pdf);
  });
  std::cout << "solid angle 3 mm under a panel of 512 triangles: " << omega << ", E[1/pdf] " << est.mean << " +- "
            << est.standard_error << "\n";
  EXPECT_NEAR(est.mean, omega, 4.0 * est.standard_error + 1e-3 * omega);
  EXPECT_NEAR(est.mean / omega, 1.0, 0.02);
}

// The polygon's part above the plane through the origin with normal n (one plane of
// Sutherland and Hodgman's clipping).
std::vector<glm::dvec3> above_plane(const std::vector<glm::dvec3>& polygon, const glm::dvec3& n) {
  std::vector<glm::dvec3> out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3& a = polygon[i];
    const glm::dvec3& b = polygon[(i + 1) % polygon.size()];
    const double da = glm::dot(a, n), db = glm::dot(b, n);
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// Irradiance 2 mm from a one-sided tessellated sphere lamp (radiance 1), by Lambert's
// formula over the triangles that face the point, clipped at its horizon.
double sphere_irradiance(const scenes::Mesh& mesh, const glm::vec3& reference, const glm::vec3& normal) {
  double sum = 0.0;
  for (const glm::uvec3& t : mesh.triangles) {
    std::vector<glm::dvec3> v;
    for (unsigned i : {t.x, t.y, t.z}) v.push_back(glm::dvec3(mesh.positions[i]) - glm::dvec3(reference));
    if (glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), v[0]) >= 0.0) continue;  // seen from behind
    const std::vector<glm::dvec3> clipped = above_plane(v, glm::dvec3(normal));
    if (clipped.size() >= 3) sum += test::polygon_irradiance(clipped, glm::dvec3(normal), 1.0);
  }
  return sum;
}

TEST(EmitterTree, LightSamplingBesideASphereLampIsUnbiased) {
  const glm::vec3 centre(0.0f, 2.0f, 0.0f);
  scenes::Scene scene;
  test::add_uv_sphere(scene, centre, 0.1f, test::add_material(scene, test::make_emitter(glm::vec3(1.0f))), 32, 16);
  const EmitterSampler sampler(scene);
  const glm::vec3 reference = centre + glm::vec3(0.102f, 0.0f, 0.0f);
  // Facing the lamp, and tilted 73 degrees from it (its far side below the horizon).
  for (const glm::vec3& normal : {glm::vec3(-1.0f, 0.0f, 0.0f), glm::normalize(glm::vec3(-0.3f, 1.0f, 0.0f))}) {
    const double exact = sphere_irradiance(scene.meshes[0], reference, normal);
    Rng rng(23, 1);
    const test::MeanAndError est = test::monte_carlo(200000, [&](int) {
      EmitterSample s;
      if (!sampler.sample(reference, rng.next_float(), rng.next_2d(), &s)) return 0.0;
      return double(s.radiance.x) * std::max(0.0, double(glm::dot(s.wi, normal))) / double(s.pdf);
    });
    std::cout << "irradiance 2 mm from a sphere lamp, normal (" << normal.x << ", " << normal.y << "): exact " << exact
              << ", sampled " << est.mean << " +- " << est.standard_error << "\n";
    EXPECT_NEAR(est.mean, exact, 4.0 * est.standard_error + 2e-3 * exact);
  }
}

}  // namespace
}  // namespace phyir::render
