// The directional quadtree (render/guiding): its density integrates to one over the sphere,
// its samples follow its density (chi-square), a tree trained on a bright cone puts its mass
// there, and an empty tree is uniform.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "phyir/core/pcg32.h"
#include "phyir/core/safe_math.h"
#include "phyir/render/guiding/cylindrical_map.h"
#include "phyir/render/guiding/directional_quadtree.h"
#include "render/chi_square.h"

namespace phyir::render::guiding {
namespace {

const glm::vec3 kConeAxis = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
constexpr float kConeCos = 0.97f;  // a cone of ~14 degrees: (1 - 0.97) / 2 = 1.5% of the sphere

// A uniform direction on the sphere.
glm::vec3 uniform_direction(Pcg32* rng) { return square_to_direction(rng->next_2d()); }

// Records of incident radiance 100 inside the cone and 1 elsewhere, drawn uniformly
// (density 1 / 4 pi), over three passes so the structure refines as in rendering.
DirectionalQuadtree trained_on_cone(int records_per_pass = 20000) {
  Pcg32 rng(7, 1);
  DirectionalQuadtree tree;
  for (int pass = 0; pass < 3; ++pass) {
    DirectionalQuadtree building = tree.refined();
    for (int i = 0; i < records_per_pass; ++i) {
      const glm::vec3 d = uniform_direction(&rng);
      const double radiance = glm::dot(d, kConeAxis) > kConeCos ? 100.0 : 1.0;
      building.record(direction_to_square(d), radiance * 4.0 * kPi);
    }
    tree = building;
    tree.finalize();
  }
  return tree;
}

TEST(DirectionalQuadtree, EmptyTreeIsUniform) {
  const DirectionalQuadtree tree;
  EXPECT_EQ(tree.total(), 0.0);
  EXPECT_FLOAT_EQ(tree.pdf(glm::vec3(0, 0, 1)), 1.0f / (4.0f * kPi));
  EXPECT_FLOAT_EQ(tree.pdf_square(glm::vec2(0.9f, 0.1f)), 1.0f);
  const glm::vec2 p = tree.sample_square(glm::vec2(0.25f, 0.75f));
  EXPECT_FLOAT_EQ(p.x, 0.25f);
  EXPECT_FLOAT_EQ(p.y, 0.75f);
  // Refining an empty tree gives an empty tree, not a crash or NaN.
  EXPECT_EQ(tree.refined().node_count(), 1u);
}

TEST(DirectionalQuadtree, SamplesItsLastFinalize) {
  DirectionalQuadtree tree;
  tree.record(glm::vec2(0.1f, 0.1f), 5.0);
  // Recorded, not finalized: still uniform.
  EXPECT_FLOAT_EQ(tree.pdf_square(glm::vec2(0.9f, 0.9f)), 1.0f);
  tree.finalize();
  EXPECT_FLOAT_EQ(tree.pdf_square(glm::vec2(0.1f, 0.1f)), 4.0f);
  EXPECT_FLOAT_EQ(tree.pdf_square(glm::vec2(0.9f, 0.9f)), 0.0f);
  const glm::vec2 p = tree.sample_square(glm::vec2(0.7f, 0.3f));
  EXPECT_LT(p.x, 0.5f);
  EXPECT_LT(p.y, 0.5f);
}

TEST(DirectionalQuadtree, MapIsInverse) {
  Pcg32 rng(3, 3);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 p = rng.next_2d();
    const glm::vec2 q = direction_to_square(square_to_direction(p));
    EXPECT_NEAR(p.x, q.x, 1e-5f);
    EXPECT_NEAR(std::fmod(p.y - q.y + 1.5f, 1.0f) - 0.5f, 0.0f, 1e-5f);
  }
}

TEST(DirectionalQuadtree, PdfIntegratesToOneOverTheSphere) {
  const DirectionalQuadtree tree = trained_on_cone();
  ASSERT_GT(tree.depth(), 3);
  // Midpoint rule on a (theta, phi) grid, independent of the tree's cylindrical map.
  const test::SphereGrid grid(glm::vec3(0, 0, 1), 1.0f, 256, 512);
  const double integral = grid.integrate([&](const glm::vec3& d) { return double(tree.pdf(d)); }, 4);
  EXPECT_NEAR(integral, 1.0, 5e-3);
}

TEST(DirectionalQuadtree, SamplesFollowThePdf) {
  const DirectionalQuadtree tree = trained_on_cone();
  // Cells of the square at 2^-6: the grid lines fall on the tree's cell edges to depth 6,
  // and 16 x 16 midpoints per cell integrate the piecewise-constant pdf exactly to depth 10.
  constexpr int kGrid = 64, kSub = 16, kSamples = 500000;
  std::vector<double> observed(kGrid * kGrid, 0.0), expected(kGrid * kGrid, 0.0);
  for (int c = 0; c < kGrid * kGrid; ++c) {
    for (int s = 0; s < kSub * kSub; ++s) {
      const glm::vec2 p((c % kGrid + (s % kSub + 0.5f) / kSub) / kGrid, (c / kGrid + (s / kSub + 0.5f) / kSub) / kGrid);
      expected[c] += tree.pdf_square(p) / double(kSub * kSub * kGrid * kGrid) * kSamples;
    }
  }
  Pcg32 rng(11, 5);
  for (int i = 0; i < kSamples; ++i) {
    const glm::vec2 p = tree.sample_square(rng.next_2d());
    ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f);
    observed[int(p.y * kGrid) * kGrid + int(p.x * kGrid)] += 1.0;
  }
  const test::ChiSquareResult r = test::chi_square_test(observed, expected);
  EXPECT_TRUE(r.passed()) << r.message;
}

TEST(DirectionalQuadtree, SampleAndPdfAgreeOnTheSphere) {
  const DirectionalQuadtree tree = trained_on_cone();
  Pcg32 rng(5, 9);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec2 u = rng.next_2d();
    const glm::vec3 d = tree.sample(u);
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    EXPECT_GT(tree.pdf(d), 0.0f);  // a sampled direction is never one the pdf calls impossible
  }
}

TEST(DirectionalQuadtree, TrainedOnABrightConePutsItsMassThere) {
  const DirectionalQuadtree tree = trained_on_cone();
  // The cone holds 100 x 1.5% / (100 x 1.5% + 98.5%) = 60% of the energy; the guide's mass
  // there must approach it (a uniform guide would put 1.5% there), less what its cells
  // straddling the cone's edge put outside.
  Pcg32 rng(13, 2);
  int inside = 0;
  constexpr int kSamples = 100000;
  for (int i = 0; i < kSamples; ++i) inside += glm::dot(tree.sample(rng.next_2d()), kConeAxis) > kConeCos;
  const double fraction = double(inside) / kSamples;
  EXPECT_GT(fraction, 0.45);
  EXPECT_LT(fraction, 0.62);
  EXPECT_GT(tree.pdf(kConeAxis), 20.0f / (4.0f * kPi));
}

TEST(DirectionalQuadtree, RefinementFollowsTheEnergy) {
  const DirectionalQuadtree tree = trained_on_cone();
  const DirectionalQuadtree refined = tree.refined();
  EXPECT_EQ(refined.total(), 0.0);  // structure only
  EXPECT_GT(refined.node_count(), 1u);
  // rho = 1%: no more leaves than 4 per 1% of energy, plus the tree's internal nodes.
  EXPECT_LT(refined.node_count(), 400u);
  // A much larger threshold keeps the tree shallow.
  EXPECT_LT(tree.refined(0.3f).node_count(), refined.node_count());
  EXPECT_LE(tree.refined(0.01f, 3).depth(), 3);
}

}  // namespace
}  // namespace phyir::render::guiding
