// EmitterCoverage: the exact mean emission over a probe texel against dense sampling of the
// lights' per-direction indicator (hits()), the whole sphere's sum against the light's solid
// angle by Van Oosterom and Strackee's formula, and the parts the probe renderer samples in.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "phyir/core/safe_math.h"
#include "emitter_coverage.h"
#include "phyir/render/equirect.h"
#include "phyir/render/probe_grid.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

constexpr int kH = 16, kW = 32;

struct Case {
  const char* name;
  glm::vec3 origin;
  glm::vec3 corner, edge_u, edge_v;  // a quad light (two triangles)
};

// Lights seen from the side, across the phi seam (-Z... +Z behind: phi = +-pi at +Z),
// surrounding the zenith, with an edge passing 1 mm from the zenith, very close, and small.
const Case kCases[] = {
    {"wall light", glm::vec3(0.0f), glm::vec3(1.0f, -0.83f, -0.71f), glm::vec3(0, 1.9f, 0), glm::vec3(0, 0, 1.7f)},
    {"across the seam", glm::vec3(0.0f), glm::vec3(-0.4f, -0.3f, 1.2f), glm::vec3(0.9f, 0, 0), glm::vec3(0, 0.8f, 0)},
    {"around the zenith", glm::vec3(0.1f, 0.0f, -0.05f), glm::vec3(-0.3f, 2.6f, -0.3f), glm::vec3(0, 0, 0.6f),
     glm::vec3(0.6f, 0, 0)},
    {"edge over the zenith", glm::vec3(0.299f, 0.0f, 0.0f), glm::vec3(-0.3f, 2.6f, -0.3f), glm::vec3(0, 0, 0.6f),
     glm::vec3(0.6f, 0, 0)},
    {"7 cm from the light", glm::vec3(0.37f, 2.55f, 0.0f), glm::vec3(-0.3f, 2.6f, -0.3f), glm::vec3(0, 0, 0.6f),
     glm::vec3(0.6f, 0, 0)},
    // Two degrees across: its edges are traced with few points (emitter_coverage.cpp).
    {"small and far", glm::vec3(0.0f), glm::vec3(2.0f, 0.3f, -3.0f), glm::vec3(0.12f, 0, 0), glm::vec3(0, 0.1f, 0)},
};

TEST(EmitterCoverage, TexelMeansMatchDenseSamplingAndSumToTheLightsSolidAngle) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    scenes::Scene scene;
    const glm::vec3 Le(3.0f, 2.0f, 1.0f);
    test::add_quad(scene, c.corner, c.edge_u, c.edge_v, test::add_material(scene, test::make_emitter(Le, true)), "light");
    const EmitterCoverage coverage(scene);
    ASSERT_TRUE(coverage.usable());
    const EmitterCoverage::View view = coverage.view(c.origin);
    ASSERT_TRUE(view.valid());
    std::vector<EmitterCoverage::View::Piece> pieces;
    double total = 0.0, worst = 0.0;
    for (int row = 0; row < kH; ++row)
      for (int col = 0; col < kW; ++col) {
        const glm::vec3 exact = view.texel_mean(row, col, kH, kW);
        // The lights with a part in this texel, each once (a light round a pole may have two
        // parts in one texel, one per turn of its unwrapped outline).
        view.texel_pieces(row, col, kH, kW, &pieces);
        std::map<int, float> lights;
        for (const auto& piece : pieces) lights[piece.light] = piece.emission.x;
        constexpr int n = 96;
        double sampled = 0.0;
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b) {
            const glm::vec3 d = probe_texel_direction(row, col, kH, kW, glm::vec2((a + 0.5f) / n, (b + 0.5f) / n));
            float distance = 0.0f;
            for (const auto& [light, emission] : lights)
              if (view.hits(light, d, &distance)) sampled += emission;
          }
        sampled /= n * n;
        worst = std::max(worst, std::abs(sampled - exact.x) / Le.x);
        EXPECT_NEAR(exact.y / Le.y, exact.x / Le.x, 1e-5);
        total += exact.x / Le.x * equirect_texel_solid_angle(row, kW, kH);
      }
    // A 96 x 96 grid resolves a straight edge through a texel to ~1% of the texel.
    EXPECT_LT(worst, 0.02);
    const glm::dvec3 o(c.origin), p0 = glm::dvec3(c.corner) - o, u(c.edge_u), v(c.edge_v);
    const double omega =
        test::triangle_solid_angle(p0, p0 + u, p0 + u + v) + test::triangle_solid_angle(p0, p0 + u + v, p0 + v);
    EXPECT_NEAR(total, omega, 2e-4 * omega) << "largest texel difference to sampling " << worst;
  }
}

// The pieces the probe renderer samples the emission in: each piece's box holds its part of
// the texel (points of the box inside the triangle, scaled by the box's share of the texel,
// give the piece's exact fraction back), and hits() reports the distance to a point that
// lies on the light.
TEST(EmitterCoverage, EachPieceBoxesItsPartAndHitsLandsOnTheLight) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    scenes::Scene scene;
    test::add_quad(scene, c.corner, c.edge_u, c.edge_v, test::add_material(scene, test::make_emitter(glm::vec3(2.0f), true)),
                   "light");
    const EmitterCoverage::View view = EmitterCoverage(scene).view(c.origin);
    ASSERT_TRUE(view.valid());
    std::vector<EmitterCoverage::View::Piece> pieces;
    int checked = 0;
    double worst = 0.0, worst_plane = 0.0;
    for (int row = 0; row < kH; ++row)
      for (int col = 0; col < kW; ++col) {
        view.texel_pieces(row, col, kH, kW, &pieces);
        double sum = 0.0;
        for (const auto& piece : pieces) {
          sum += piece.fraction;
          constexpr int n = 64;
          int inside = 0;
          for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
              const double phi = piece.lo.x + (a + 0.5) / n * (piece.hi.x - piece.lo.x);
              const double z = piece.lo.y + (b + 0.5) / n * (piece.hi.y - piece.lo.y);
              const glm::vec3 d = equirect_direction(float(phi / kTwoPi + 0.5), float(z), float(std::sqrt(1.0 - z * z)));
              float t = 0.0f;
              if (!view.hits(piece.light, d, &t)) continue;
              ++inside;
              // The point lies in the quad's plane, inside the quad.
              const glm::vec3 q = c.origin + t * d - c.corner;
              const glm::vec3 n_quad = glm::normalize(glm::cross(c.edge_u, c.edge_v));
              worst_plane = std::max(worst_plane, double(std::abs(glm::dot(q, n_quad))));
              const float u = glm::dot(q, c.edge_u) / glm::dot(c.edge_u, c.edge_u);
              const float v = glm::dot(q, c.edge_v) / glm::dot(c.edge_v, c.edge_v);
              EXPECT_TRUE(u > -1e-3f && u < 1.001f && v > -1e-3f && v < 1.001f) << u << " " << v;
            }
          const double z0 = std::cos(kPi * (row + 1) / kH), z1 = std::cos(kPi * row / kH);
          const double box = (piece.hi.x - piece.lo.x) * (piece.hi.y - piece.lo.y) / ((kTwoPi / kW) * (z1 - z0));
          worst = std::max(worst, std::abs(double(inside) / (n * n) * box - piece.fraction));
          ++checked;
        }
        EXPECT_NEAR(sum * 2.0, view.texel_mean(row, col, kH, kW).x, 1e-5);
      }
    EXPECT_GT(checked, 0);
    // A 64 x 64 grid of the box resolves an edge through it to ~2% of the box.
    EXPECT_LT(worst, 0.02);
    EXPECT_LT(worst_plane, 1e-4);
  }
}

TEST(EmitterCoverage, OneSidedLightsAreOnlySeenFromTheFrontAndTexturedOnesAreNotUsable) {
  scenes::Scene scene;
  // cross(edge_u, edge_v) = -Y: emits downwards.
  test::add_quad(scene, glm::vec3(-0.3f, 2.6f, -0.3f), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0, 0.6f),
                 test::add_material(scene, test::make_emitter(glm::vec3(5.0f))), "light");
  const EmitterCoverage coverage(scene);
  const EmitterCoverage::View below = coverage.view(glm::vec3(0.05f, 0.0f, 0.02f));
  const EmitterCoverage::View above = coverage.view(glm::vec3(0.05f, 3.0f, 0.02f));
  ASSERT_TRUE(below.valid());
  ASSERT_TRUE(above.valid());
  // Straight under the panel's diagonal the zenith lies on an arc, where phi is undefined:
  // the view says so (its probe keeps the plain estimate).
  EXPECT_FALSE(coverage.view(glm::vec3(0.0f)).valid());
  EXPECT_GT(below.texel_mean(0, 0, kH, kW).x, 0.0f);
  EXPECT_EQ(above.texel_mean(kH - 1, 0, kH, kW).x, 0.0f);

  scenes::Scene textured = scene;
  textured.materials[0].emissive_texture.texture = 0;
  EXPECT_FALSE(EmitterCoverage(textured).usable());
  EXPECT_FALSE(EmitterCoverage(scenes::Scene{}).usable());
}

// A double-sided light made of a quad and its copy wound the other way covers a texel once.
TEST(EmitterCoverage, TwinTrianglesOfADoubleSidedLightCountOnce) {
  scenes::Scene single;
  test::add_quad(single, glm::vec3(-0.3f, 2.6f, -0.3f), glm::vec3(0.6f, 0, 0), glm::vec3(0, 0, 0.6f),
                 test::add_material(single, test::make_emitter(glm::vec3(5.0f), true)), "light");
  scenes::Scene twinned = single;
  scenes::Mesh twin = single.meshes[0];
  for (glm::uvec3& t : twin.triangles) std::swap(t.y, t.z);
  test::add_mesh(twinned, std::move(twin));
  EXPECT_EQ(light_triangles(twinned).size(), 2u);
  const glm::vec3 origin(0.05f, 0.0f, 0.02f);
  const EmitterCoverage::View one = EmitterCoverage(single).view(origin);
  const EmitterCoverage::View two = EmitterCoverage(twinned).view(origin);
  ASSERT_TRUE(one.valid() && two.valid());
  int covered = 0;
  for (int row = 0; row < kH; ++row)
    for (int col = 0; col < kW; ++col) {
      EXPECT_EQ(two.texel_mean(row, col, kH, kW), one.texel_mean(row, col, kH, kW));
      covered += one.texel_mean(row, col, kH, kW).x > 0.0f;
    }
  EXPECT_GT(covered, 0);
}

// A lamp shade of thousands of small glowing triangles (real furniture's lamps at night):
// no coverage is traced, so a probe inside it does not trace every triangle it sees.
TEST(EmitterCoverage, ScenesWithThousandsOfLightTrianglesAreNotTraced) {
  scenes::Scene shade;
  const int material = test::add_material(shade, test::make_emitter(glm::vec3(1.0f)));
  for (int k = 0; k < 2100; ++k) {  // 4200 triangles
    const float a = 0.003f * float(k);
    test::add_quad(shade, glm::vec3(std::cos(a), 0.5f, std::sin(a)), glm::vec3(0.0f, 0.1f, 0.0f),
                   glm::vec3(-0.003f * std::sin(a), 0.0f, 0.003f * std::cos(a)), material, "shade");
  }
  EXPECT_FALSE(EmitterCoverage(shade).usable());
  shade.meshes.resize(1000);  // 2000 triangles: traced
  EXPECT_TRUE(EmitterCoverage(shade).usable());
}

}  // namespace
}  // namespace phyir::render
