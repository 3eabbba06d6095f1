// EmitterFootprints: the texels of a probe a light may cover, and among them those its
// outline crosses, against the coverage of every texel computed by dense sampling.
#include <gtest/gtest.h>

#include <iostream>
#include <vector>

#include "emitter_footprints.h"
#include "phyir/render/equirect.h"
#include "phyir/render/probe_grid.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

// The light: the rectangle x = 1, y in [-0.83, 1.07], z in [-0.71, 0.99] (its edges off the
// texel borders), seen from the origin.
constexpr float kY0 = -0.83f, kY1 = 1.07f, kZ0 = -0.71f, kZ1 = 0.99f;

// Fraction of texel (row, col) of an h x w probe at the origin the light covers (a 64 x 64
// grid of directions uniform in solid angle).
double square_coverage(int row, int col, int h, int w) {
  constexpr int n = 64;
  int hits = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const glm::vec3 d = probe_texel_direction(row, col, h, w, glm::vec2((a + 0.5f) / n, (b + 0.5f) / n));
      if (!(d.x > 0.0f)) continue;
      const float y = d.y / d.x, z = d.z / d.x;
      if (y >= kY0 && y <= kY1 && z >= kZ0 && z <= kZ1) ++hits;
    }
  return double(hits) / (n * n);
}

TEST(EmitterFootprints, PartlyCoveredTexelsAreEdgesFullyCoveredOnesAreCovered) {
  scenes::Scene scene;
  const int light = test::add_material(scene, test::make_emitter(glm::vec3(10.0f), /*double_sided=*/true));
  test::add_quad(scene, glm::vec3(1.0f, kY0, kZ0), glm::vec3(0, kY1 - kY0, 0), glm::vec3(0, 0, kZ1 - kZ0), light,
                 "wall light");
  const EmitterFootprints footprints(scene);
  const int h = 16, w = 32;
  std::vector<uint8_t> flags(size_t(h) * w, 0);
  footprints.mark(glm::vec3(0.0f), h, w, &flags);
  int full = 0, partial = 0, edges = 0, inner_covered = 0;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const double coverage = square_coverage(r, c, h, w);
      const uint8_t f = flags[size_t(r) * w + c];
      edges += f == EmitterFootprints::kEdge;
      if (coverage > 0.999) {
        ++full;
        EXPECT_GE(f, EmitterFootprints::kCovered) << r << "," << c;
        if (f == EmitterFootprints::kCovered) ++inner_covered;
      } else if (coverage > 0.01) {
        ++partial;
        EXPECT_EQ(f, EmitterFootprints::kEdge) << r << "," << c << " coverage " << coverage;
      }
    }
  // The light spans ~90 degrees: ~8 rows by ~8 columns of 11.25-degree texels, of which
  // the inner ones are whole; the panel's diagonal is not an outline, so they stay kCovered.
  EXPECT_GT(full, 8);
  EXPECT_GT(partial, 8);
  EXPECT_GT(inner_covered, 8);
  // The outline's texels are found from points on it, so edge texels are (nearly) only
  // partly covered ones: a few may hold a sliver below the 1% counted above.
  EXPECT_LE(edges, partial + 4);
  std::cout << full << " texels fully covered, " << partial << " partly, " << edges << " marked as edges\n";
}

TEST(EmitterFootprints, NeitherADiagonalInsideAPanelNorACreaseSeenFromBothFrontsIsAnOutline) {
  // One mesh of two triangles sharing the edge v0-v2 (by index); flat, that edge is the
  // panel's diagonal; with v3 pulled towards the probe, it is a crease whose two sides both
  // face the probe: the light continues across it.
  for (bool bent : {false, true}) {
    scenes::Scene scene;
    scenes::Mesh mesh;
    mesh.name = "panel";
    mesh.material = test::add_material(scene, test::make_emitter(glm::vec3(10.0f), true));
    mesh.positions = {{1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {bent ? 0.5f : 1.0f, 1, -1}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(mesh);
    const EmitterFootprints footprints(scene);
    const int h = 16, w = 32;
    std::vector<uint8_t> flags(size_t(h) * w, 0);
    footprints.mark(glm::vec3(0.0f), h, w, &flags);
    // The texel of a point a quarter of the way along the shared edge.
    const glm::vec2 uv = equirect_uv(glm::normalize(glm::vec3(1.0f, -0.5f, -0.5f)));
    const uint8_t f = flags[size_t(uv.y * h) * w + size_t(uv.x * w)];
    EXPECT_EQ(f, EmitterFootprints::kCovered) << (bent ? "bent" : "flat");
  }
}

TEST(EmitterFootprints, ACreaseIsAnOutlineWhereOneSideTurnsAway) {
  // The corner of a box light: faces x = 1 (normal +X) and z = 1 (normal +Z), one-sided, each
  // with its own vertices (as exporters split them at a crease: matched by position). From
  // (3, 0, 3) both faces are in view and the light continues across the crease; from
  // (3, 0, 0.5) the +Z face turns away and the crease is the light's outline.
  scenes::Scene scene;
  scenes::Mesh mesh;
  mesh.name = "box corner";
  mesh.material = test::add_material(scene, test::make_emitter(glm::vec3(10.0f)));
  mesh.positions = {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1},     // x = 1
                    {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}, {-1, -1, 1}};  // z = 1
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  scene.meshes.push_back(mesh);
  const EmitterFootprints footprints(scene);
  const int h = 16, w = 32;
  for (const auto& [origin, expected] : {std::pair{glm::vec3(3.0f, 0.0f, 3.0f), EmitterFootprints::kCovered},
                                         std::pair{glm::vec3(3.0f, 0.0f, 0.5f), EmitterFootprints::kEdge}}) {
    std::vector<uint8_t> flags(size_t(h) * w, 0);
    footprints.mark(origin, h, w, &flags);
    // The texel of a point a quarter of the way up the crease.
    const glm::vec2 uv = equirect_uv(glm::normalize(glm::vec3(1.0f, -0.5f, 1.0f) - origin));
    EXPECT_EQ(flags[size_t(uv.y * h) * w + size_t(uv.x * w)], expected) << origin.z;
  }
}

// Fraction of texel (row, col) of an h x w probe at `origin` that the sphere (centre, radius)
// covers (a 32 x 32 grid of directions).
double sphere_coverage(const glm::vec3& origin, const glm::vec3& centre, float radius, int row, int col, int h, int w) {
  constexpr int n = 32;
  int hits = 0;
  const glm::vec3 oc = centre - origin;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const glm::vec3 d = probe_texel_direction(row, col, h, w, glm::vec2((a + 0.5f) / n, (b + 0.5f) / n));
      const float along = glm::dot(oc, d);
      hits += along > 0.0f && glm::dot(oc, oc) - along * along <= radius * radius;
    }
  return double(hits) / (n * n);
}

TEST(EmitterFootprints, ManyTriangleLightsFarOrNearMarkEveryTexelTheyCover) {
  // A lamp shade of real furniture has thousands of emissive triangles: far away they are
  // marked as clusters (a cap per cluster), near as triangles. Either way no texel a light
  // covers may be missed, towards the horizon, over a pole, or from inside the lamp's reach.
  const int h = 16, w = 32;
  const float radius = 0.2f;
  for (const glm::vec3 centre : {glm::vec3(3.0f, 0.4f, -1.0f), glm::vec3(0.05f, 2.5f, 0.0f),
                                 glm::vec3(-0.1f, -0.3f, 0.35f), glm::vec3(0.0f, 0.0f, 40.0f)}) {
    scenes::Scene scene;
    const int light = test::add_material(scene, test::make_emitter(glm::vec3(10.0f), true));
    test::add_uv_sphere(scene, centre, radius, light, 64, 32, false, "lamp shade");  // ~4000 triangles
    const EmitterFootprints footprints(scene);
    std::vector<uint8_t> flags(size_t(h) * w, 0);
    footprints.mark(glm::vec3(0.0f), h, w, &flags);
    int covered = 0, marked = 0;
    for (int r = 0; r < h; ++r)
      for (int c = 0; c < w; ++c) {
        // The tessellated sphere holds the sphere of radius cos(pi / 32) times its own.
        const bool seen = sphere_coverage(glm::vec3(0.0f), centre, radius * 0.99f, r, c, h, w) > 0.0;
        const uint8_t f = flags[size_t(r) * w + c];
        covered += seen;
        marked += f != 0;
        if (seen) {
          EXPECT_NE(f, 0) << "light at " << centre.x << "," << centre.y << "," << centre.z << " texel " << r << ","
                          << c;
        }
      }
    EXPECT_GT(covered, 0);
    // Far and small, a light is marked where its cap falls, not everywhere.
    if (glm::length(centre) > 10.0f) {
      EXPECT_LE(marked, 16) << "far light";
    }
  }
}

}  // namespace
}  // namespace phyir::render
