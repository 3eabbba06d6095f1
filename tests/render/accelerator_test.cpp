// The Embree accelerator and robust spawn points: exact distances, no self-intersection
// near and far from the origin, no leaks through 1 mm geometry, agreement between the
// closest-hit, any-hit and packet paths, and robustness to bad meshes.
#include "phyir/render/accelerator.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <iostream>
#include <limits>

#include "phyir/core/safe_math.h"
#include "phyir/render/frame.h"
#include "phyir/render/ray_offset.h"
#include "phyir/render/render_scene.h"
#include "phyir/render/rng.h"
#include "phyir/render/sampling.h"
#include "test_scenes.h"

namespace phyir::render {
namespace {

using test::add_box;
using test::add_material;
using test::add_quad;
using test::add_uv_sphere;
using test::make_box_room;
using test::make_material;

const glm::vec3 kRoomMin(-2.0f, 0.0f, -1.5f), kRoomMax(2.0f, 3.0f, 1.5f);

glm::vec3 random_in_box(Rng& rng, const glm::vec3& lo, const glm::vec3& hi) {
  return lo + (hi - lo) * glm::vec3(rng.next_float(), rng.next_float(), rng.next_float());
}

// Distance from an inside point to the room's walls along d, and which wall (mesh index in
// make_box_room's order -X, +X, -Y, +Y, -Z, +Z).
double analytic_wall_distance(const glm::vec3& o, const glm::vec3& d, int* wall) {
  double best = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    if (d[axis] == 0.0f) continue;
    const double bound = d[axis] > 0.0f ? kRoomMax[axis] : kRoomMin[axis];
    const double t = (bound - double(o[axis])) / double(d[axis]);
    if (t < best) {
      best = t;
      *wall = 2 * axis + (d[axis] > 0.0f ? 1 : 0);
    }
  }
  return best;
}

TEST(Accelerator, DistanceToWallsAlongAxes) {
  const scenes::Scene scene = make_box_room(kRoomMin, kRoomMax);
  const Accelerator accel(scene);
  const glm::vec3 o(0.3f, 1.2f, -0.4f);
  const struct {
    glm::vec3 d;
    float t;
    int wall;
  } cases[] = {{{1, 0, 0}, 1.7f, 1}, {{-1, 0, 0}, 2.3f, 0}, {{0, 1, 0}, 1.8f, 3},
               {{0, -1, 0}, 1.2f, 2}, {{0, 0, 1}, 1.9f, 5}, {{0, 0, -1}, 1.1f, 4}};
  for (const auto& c : cases) {
    Hit hit;
    ASSERT_TRUE(accel.intersect(Ray{o, c.d}, &hit));
    EXPECT_NEAR(hit.t, c.t, 1e-4f * c.t);
    EXPECT_EQ(hit.mesh, c.wall);
    EXPECT_GE(hit.triangle, 0);
    EXPECT_LE(hit.triangle, 1);
  }
}

TEST(Accelerator, DistanceToWallsRandomRays) {
  const scenes::Scene scene = make_box_room(kRoomMin, kRoomMax);
  const Accelerator accel(scene);
  Rng rng(1, 2);
  double worst = 0.0;
  int wrong_wall = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 o = random_in_box(rng, kRoomMin + 0.01f, kRoomMax - 0.01f);
    const glm::vec3 d = sample_uniform_sphere(rng.next_2d());
    int wall = -1;
    const double expected = analytic_wall_distance(o, d, &wall);
    Hit hit;
    ASSERT_TRUE(accel.intersect(Ray{o, d}, &hit)) << "ray " << i << " escaped the closed room";
    worst = std::max(worst, std::abs(hit.t - expected) / expected);
    // A ray into an edge of the room may report the neighbouring wall: accept it only if
    // the hit point also lies on the expected wall's plane.
    if (hit.mesh != wall) {
      const int axis = wall / 2;
      const float plane = (wall % 2) ? kRoomMax[axis] : kRoomMin[axis];
      if (std::abs(o[axis] + hit.t * d[axis] - plane) > 1e-4f) ++wrong_wall;
    }
  }
  std::cout << "worst relative distance error " << worst << "\n";
  EXPECT_LT(worst, 1e-4) << "worst relative distance error";
  EXPECT_EQ(wrong_wall, 0);
}

// Shoots `n` rays at random points of a square quad (corner c, edges eu, ev), spawns a ray
// in a random direction leaving the surface on either side and counts hits on the quad.
struct SelfHitCounts {
  int offset = 0;  // with spawn_origin
  int raw = 0;     // from the unmodified hit point (the sensitivity check)
  int primary_misses = 0;
};

SelfHitCounts count_self_intersections(const glm::vec3& c, const glm::vec3& eu, const glm::vec3& ev, int n) {
  scenes::Scene scene;
  add_quad(scene, c, eu, ev, add_material(scene, make_material()));
  const RenderScene rs(scene);
  const glm::vec3 normal = glm::normalize(glm::cross(eu, ev));
  const float size = glm::length(eu);
  Rng rng(42, 3);
  SelfHitCounts counts;
  for (int i = 0; i < n; ++i) {
    // A primary ray from a random point above or below the quad to a random point on it.
    const glm::vec3 target = c + eu * (0.05f + 0.9f * rng.next_float()) + ev * (0.05f + 0.9f * rng.next_float());
    const float side = rng.next_float() < 0.5f ? 1.0f : -1.0f;
    const glm::vec3 eye = target + side * size * normal + 0.25f * size * sample_uniform_sphere(rng.next_2d());
    Ray primary{eye, glm::normalize(target - eye)};
    SurfaceInteraction si;
    if (!rs.trace(primary, &si)) {
      ++counts.primary_misses;
      continue;
    }
    // A direction leaving the surface, reflected or transmitted, uniformly over the
    // hemisphere (grazing ones included).
    glm::vec3 local = sample_uniform_sphere(rng.next_2d());
    if (local.z == 0.0f) local.z = 1e-6f;
    const glm::vec3 d = Frame(si.geometric_normal).to_world(local);
    Hit hit;
    if (rs.accelerator().intersect(Ray{spawn_origin(si.position, si.geometric_normal, d), d}, &hit)) ++counts.offset;
    if (rs.accelerator().intersect(Ray{si.position, d}, &hit)) ++counts.raw;
  }
  return counts;
}

TEST(RayOffset, NoSelfIntersectionFarFromOrigin) {
  // A tilted 10 m quad 1e4 m from the origin, where a float ULP is ~1 mm.
  const glm::vec3 c(1.0e4f, 2.0e3f, -1.0e4f);
  const glm::vec3 eu = glm::normalize(glm::vec3(1.0f, 0.3f, 0.2f)) * 10.0f;
  const glm::vec3 ev = glm::normalize(glm::cross(glm::vec3(0.1f, 0.2f, 1.0f), eu)) * 10.0f;
  const SelfHitCounts counts = count_self_intersections(c, eu, ev, 100000);
  EXPECT_EQ(counts.primary_misses, 0);
  EXPECT_EQ(counts.offset, 0) << "self-intersections with spawn_origin";
  // Without the offset a large share of rays hit their own surface: the test can fail.
  EXPECT_GT(counts.raw, 1000) << "the unoffset origin should self-intersect";
  std::cout << "self-hits in 1e5 rays: " << counts.offset << " with spawn_origin, " << counts.raw
            << " from the raw hit point\n";
}

TEST(RayOffset, NoSelfIntersectionNearOrigin) {
  // A tilted 1 m quad straddling the origin (coordinates cross zero, the fixed-offset branch).
  const glm::vec3 eu = glm::normalize(glm::vec3(1.0f, 0.3f, 0.2f));
  const glm::vec3 ev = glm::normalize(glm::cross(glm::vec3(0.1f, 0.2f, 1.0f), eu));
  const glm::vec3 c = -0.5f * (eu + ev);
  const SelfHitCounts counts = count_self_intersections(c, eu, ev, 100000);
  EXPECT_EQ(counts.primary_misses, 0);
  EXPECT_EQ(counts.offset, 0) << "self-intersections with spawn_origin";
  EXPECT_GT(counts.raw, 1000) << "the unoffset origin should self-intersect";
  std::cout << "self-hits in 1e5 rays: " << counts.offset << " with spawn_origin, " << counts.raw
            << " from the raw hit point\n";
}

TEST(RayOffset, OffsetMovesToTheNormalSideByFewUlps) {
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  for (float y : {0.0f, 1e-3f, 0.5f, -3.0f, 1e4f, -1e4f}) {
    const glm::vec3 p(1.0f, y, -2.0f);
    const glm::vec3 up = offset_ray_origin(p, n);
    const glm::vec3 down = offset_ray_origin(p, -n);
    EXPECT_GT(up.y, y);
    EXPECT_LT(down.y, y);
    EXPECT_EQ(up.x, p.x);
    EXPECT_EQ(up.z, p.z);
    // 256 ULPs (int_scale) of |y|, or 1/65536 near the origin: small against any scene.
    EXPECT_LT(up.y - y, std::max(1e-4f, std::abs(y) * 1e-4f));
  }
  // spawn_origin picks the side the direction leaves on.
  EXPECT_GT(spawn_origin({0, 2, 0}, n, {0.3f, 0.1f, 0.0f}).y, 2.0f);
  EXPECT_LT(spawn_origin({0, 2, 0}, n, {0.3f, -0.1f, 0.0f}).y, 2.0f);
}

// A shadow ray from a surface to a point on a light close above it, parallel to it, must
// reach the light unoccluded at any coordinate magnitude, and still stop at a real occluder
// between them. (With only the origin offset, the offset's 256 ulps, 61 um at 2.4 m, cut
// the way to the light's plane by more than the 1e-4 x distance margin whenever the light
// was within ~0.6 m: every sample was occluded by the light itself.)
TEST(RayOffset, ShadowRayReachesANearbyLight) {
  for (const glm::vec3 centre : {glm::vec3(0.0f), glm::vec3(0.1f, 2.4f, 0.05f), glm::vec3(-7.0f, 5.0f, 30.0f),
                                 glm::vec3(300.0f, -40.0f, 100.0f)}) {
    for (float height : {0.01f, 0.2f, 0.6f, 2.0f}) {
      scenes::Scene scene;
      // A 0.4 m light facing down (cross(edge_u, edge_v) = -Y) `height` above `centre`.
      add_quad(scene, centre + glm::vec3(-0.2f, height, -0.2f), {0.4f, 0, 0}, {0, 0, 0.4f}, add_material(scene, make_material()));
      const Accelerator accel(scene);
      const glm::vec3 up(0, 1, 0), down(0, -1, 0);
      Rng rng(11, 3);
      int occluded = 0;
      for (int i = 0; i < 1000; ++i) {
        const glm::vec3 p = centre + glm::vec3(0.8f * rng.next_float() - 0.4f, 0.0f, 0.8f * rng.next_float() - 0.4f);
        const glm::vec3 q = centre + glm::vec3(0.4f * rng.next_float() - 0.2f, height, 0.4f * rng.next_float() - 0.2f);
        occluded += accel.occluded(shadow_ray_to(p, up, q, down));
      }
      EXPECT_EQ(occluded, 0) << "light " << height << " m above (" << centre.x << ", " << centre.y << ", " << centre.z << ")";
      // A plate halfway blocks them all.
      add_quad(scene, centre + glm::vec3(-1.0f, 0.5f * height, -1.0f), {2.0f, 0, 0}, {0, 0, 2.0f}, add_material(scene, make_material()));
      const Accelerator blocked(scene);
      const glm::vec3 q = centre + glm::vec3(0.0f, height, 0.0f);
      EXPECT_TRUE(blocked.occluded(shadow_ray_to(centre, up, q, down))) << height;
    }
  }
}

TEST(RayOffset, ThinSlabDoesNotLeak) {
  // A closed 2 m x 2 m slab 1 mm thick with outward normals. Rays from above must stop at
  // its top face; continued through (refraction-like), they must stop at its bottom face
  // from inside, never slip through either face or re-hit the one they left.
  const float thickness = 0.001f;
  scenes::Scene scene;
  add_box(scene, {-1.0f, 0.0f, -1.0f}, {1.0f, thickness, 1.0f}, add_material(scene, make_material()));
  const RenderScene rs(scene);
  Rng rng(5, 9);
  int leaks_top = 0, leaks_bottom = 0, wrong_face = 0, shadow_leaks = 0;
  double worst_inside_error = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 target(1.8f * rng.next_float() - 0.9f, 0.0f, 1.8f * rng.next_float() - 0.9f);
    // Elevations down to ~0.6 degrees above grazing.
    const float cos_elev = 0.01f + 0.99f * rng.next_float();
    const float phi = kTwoPi * rng.next_float();
    const float sin_elev = std::sqrt(1.0f - cos_elev * cos_elev);
    const glm::vec3 d = glm::normalize(glm::vec3(sin_elev * std::cos(phi), -cos_elev, sin_elev * std::sin(phi)));
    const glm::vec3 start = glm::vec3(target.x, thickness, target.z) - d * 0.05f;  // 5 cm before the top face
    SurfaceInteraction top;
    if (!rs.trace(Ray{start, d}, &top)) {
      ++leaks_top;
      continue;
    }
    if (std::abs(top.position.y - thickness) > 1e-6f || !top.front_face) {
      ++wrong_face;
      continue;
    }
    // Continue into the slab.
    SurfaceInteraction bottom;
    if (!rs.trace(Ray{spawn_origin(top.position, top.geometric_normal, d), d}, &bottom)) {
      ++leaks_bottom;
      continue;
    }
    if (std::abs(bottom.position.y) > 1e-6f || bottom.front_face) {
      // Side faces are legitimate exits only near the slab's edge; targets stay 10 cm away
      // and the horizontal run inside is < 0.1 m, so anything else is wrong.
      ++wrong_face;
      continue;
    }
    const double across = double(thickness) / cos_elev;
    worst_inside_error = std::max(worst_inside_error, std::abs(bottom.distance - across) / across);
    // A shadow ray from above to 1 cm below the slab is blocked.
    const glm::vec3 below = bottom.position + d * 0.01f;
    const glm::vec3 to_below = below - start;
    Ray shadow{start, glm::normalize(to_below), 0.0f, glm::length(to_below)};
    if (!rs.accelerator().occluded(shadow)) ++shadow_leaks;
  }
  EXPECT_EQ(leaks_top, 0);
  EXPECT_EQ(leaks_bottom, 0);
  EXPECT_EQ(wrong_face, 0);
  EXPECT_EQ(shadow_leaks, 0);
  // Distance across 1 mm: short by the spawn offset, 1/65536 m = 15 um along the normal
  // near the origin (Waechter & Binder's float_scale), i.e. 1.5 % of the thickness.
  std::cout << "worst relative error of the distance across the slab " << worst_inside_error << "\n";
  EXPECT_LT(worst_inside_error, 0.02) << "worst relative error of the distance across the slab";
}

// A cluttered room: walls, an inside sphere and a floating quad, for agreement tests.
scenes::Scene cluttered_room() {
  scenes::Scene scene = make_box_room(kRoomMin, kRoomMax);
  add_uv_sphere(scene, {0.5f, 1.0f, 0.2f}, 0.6f, 0, 48, 24);
  add_quad(scene, {-1.5f, 0.5f, -1.0f}, {1.0f, 0.2f, 0.0f}, {0.0f, 0.3f, 1.2f}, 0);
  return scene;
}

TEST(Accelerator, OccludedAgreesWithIntersect) {
  const scenes::Scene scene = cluttered_room();
  const Accelerator accel(scene);
  Rng rng(11, 4);
  int disagreements = 0, occluded_count = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    Ray ray{random_in_box(rng, kRoomMin + 0.01f, kRoomMax - 0.01f), sample_uniform_sphere(rng.next_2d())};
    ray.tmax = 4.0f * rng.next_float();
    Hit hit;
    const bool any = accel.occluded(ray);
    if (any != accel.intersect(ray, &hit)) ++disagreements;
    occluded_count += any ? 1 : 0;
  }
  std::cout << disagreements << " disagreements, " << occluded_count << " of " << n << " rays occluded\n";
  EXPECT_EQ(disagreements, 0);
  // Both outcomes are well represented, so the agreement means something.
  EXPECT_GT(occluded_count, n / 10);
  EXPECT_LT(occluded_count, n - n / 10);
}

TEST(Accelerator, BatchAgreesWithSingleRays) {
  scenes::Scene scene = cluttered_room();
  scene.meshes.erase(scene.meshes.begin() + 3);  // no ceiling: some rays escape
  const Accelerator accel(scene);
  Rng rng(3, 8);
  const int n = 1000;  // 62 full packets and one of 8 live lanes
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    r.origin = random_in_box(rng, kRoomMin + 0.01f, kRoomMax - 0.01f);
    r.direction = sample_uniform_sphere(rng.next_2d());
    if (rng.next_float() < 0.2f) r.tmax = rng.next_float();
  }
  std::vector<float> t(n, -1.0f);
  accel.intersect_batch(rays.data(), rays.size(), t.data());
  int misses = 0, mismatches = 0;
  for (int i = 0; i < n; ++i) {
    Hit hit;
    if (accel.intersect(rays[i], &hit)) {
      if (!(std::abs(t[i] - hit.t) <= 1e-5f * hit.t)) ++mismatches;
    } else {
      ++misses;
      if (!std::isinf(t[i])) ++mismatches;
    }
  }
  std::cout << mismatches << " mismatches, " << misses << " misses of " << n << " rays\n";
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(misses, 20);  // the open ceiling and short rays give real misses
  EXPECT_LT(misses, n - 20);
  // Batches of fewer than 16 rays only touch their own outputs.
  std::vector<float> small(5, -7.0f);
  accel.intersect_batch(rays.data(), 3, small.data());
  EXPECT_EQ(small[3], -7.0f);
  EXPECT_EQ(small[4], -7.0f);
}

TEST(Accelerator, ConcurrentQueriesMatchSerialOnes) {
  const scenes::Scene scene = cluttered_room();
  const Accelerator accel(scene);
  Rng rng(19, 4);
  const int n = 50000;
  std::vector<Ray> rays(n);
  for (Ray& r : rays) r = Ray{random_in_box(rng, kRoomMin + 0.01f, kRoomMax - 0.01f), sample_uniform_sphere(rng.next_2d())};
  std::vector<Hit> serial(n), parallel(n);
  for (int i = 0; i < n; ++i) accel.intersect(rays[i], &serial[i]);
  tbb::parallel_for(0, n, [&](int i) { accel.intersect(rays[i], &parallel[i]); });
  int differences = 0;
  for (int i = 0; i < n; ++i)
    if (serial[i].t != parallel[i].t || serial[i].mesh != parallel[i].mesh || serial[i].triangle != parallel[i].triangle)
      ++differences;
  EXPECT_EQ(differences, 0);
}

TEST(Accelerator, BadMeshesAreSkippedAndIdsStayAligned) {
  scenes::Scene scene;
  const int mat = add_material(scene, make_material());
  scenes::Mesh empty;
  empty.name = "no triangles";
  scene.meshes.push_back(empty);                                      // 0: skipped
  add_quad(scene, {-1, -1, -5}, {2, 0, 0}, {0, 2, 0}, mat, "nan");   // 1: poisoned below
  scene.meshes[1].positions[2].x = std::numeric_limits<float>::quiet_NaN();
  add_quad(scene, {-1, -1, -4}, {2, 0, 0}, {0, 2, 0}, mat, "bad index");  // 2: poisoned below
  scene.meshes[2].triangles[1].z = 99;
  scenes::Mesh degenerate;  // 3: zero-area and repeated-vertex triangles: kept, never hit
  degenerate.name = "degenerate";
  degenerate.positions = {{-1, -1, -3}, {0, 0, -3}, {1, 1, -3}, {0, 0, -3}};
  degenerate.triangles = {{0, 1, 2}, {1, 3, 1}};
  scene.meshes.push_back(degenerate);
  add_quad(scene, {-1, -1, -6}, {2, 0, 0}, {0, 2, 0}, mat, "good");  // 4
  const Accelerator accel(scene);
  Hit hit;
  ASSERT_TRUE(accel.intersect(Ray{{0.1f, 0.2f, 0.0f}, {0, 0, -1}}, &hit));
  EXPECT_EQ(hit.mesh, 4);
  EXPECT_NEAR(hit.t, 6.0f, 1e-5f);
  // Barycentrics locate the point: p = p0 + b1 (p1 - p0) + b2 (p2 - p0).
  const scenes::Mesh& good = scene.meshes[4];
  const glm::uvec3 tri = good.triangles[hit.triangle];
  const glm::vec3 p = good.positions[tri.x] * (1 - hit.barycentric.x - hit.barycentric.y) +
                      good.positions[tri.y] * hit.barycentric.x + good.positions[tri.z] * hit.barycentric.y;
  EXPECT_NEAR(p.x, 0.1f, 1e-5f);
  EXPECT_NEAR(p.y, 0.2f, 1e-5f);
}

TEST(Accelerator, EmptySceneMissesEverything) {
  const scenes::Scene scene;
  const Accelerator accel(scene);
  Hit hit;
  EXPECT_FALSE(accel.intersect(Ray{{0, 0, 0}, {0, 0, -1}}, &hit));
  EXPECT_FALSE(accel.occluded(Ray{{0, 0, 0}, {0, 0, -1}}));
  const Ray r{{0, 0, 0}, {0, 1, 0}};
  float t = 0.0f;
  accel.intersect_batch(&r, 1, &t);
  EXPECT_TRUE(std::isinf(t));
}

TEST(Accelerator, TminAndTmaxBoundTheSearch) {
  const scenes::Scene scene = make_box_room(kRoomMin, kRoomMax);
  const Accelerator accel(scene);
  Hit hit;
  const glm::vec3 o(0.0f, 1.0f, 0.0f);
  EXPECT_FALSE(accel.intersect(Ray{o, {1, 0, 0}, 0.0f, 1.9f}, &hit));
  EXPECT_FALSE(accel.occluded(Ray{o, {1, 0, 0}, 0.0f, 1.9f}));
  EXPECT_TRUE(accel.occluded(Ray{o, {1, 0, 0}, 0.0f, 2.1f}));
  EXPECT_FALSE(accel.intersect(Ray{o, {1, 0, 0}, 2.1f}, &hit));
}

TEST(Accelerator, AlphaMaskLetsRaysThroughTransparentTexels) {
  // A quad whose base-colour texture is transparent on its left half (u < 0.5), in front
  // of an opaque wall.
  scenes::Scene scene;
  scenes::Material leaf = make_material();
  leaf.alpha_mode = scenes::AlphaMode::Mask;
  leaf.alpha_cutoff = 0.5f;
  leaf.base_color_texture.texture = test::add_texture(scene, 2, 1, {{1, 1, 1, 0.1f}, {1, 1, 1, 0.9f}});
  const int leaf_mat = add_material(scene, leaf);
  const int wall_mat = add_material(scene, make_material());
  const int leaf_mesh = add_quad(scene, {-1, -1, -2}, {2, 0, 0}, {0, 2, 0}, leaf_mat, "leaf");
  const int wall_mesh = add_quad(scene, {-5, -5, -4}, {10, 0, 0}, {0, 10, 0}, wall_mat, "wall");
  const Accelerator accel(scene);
  Hit hit;
  ASSERT_TRUE(accel.intersect(Ray{{-0.5f, 0.0f, 0.0f}, {0, 0, -1}}, &hit));
  EXPECT_EQ(hit.mesh, wall_mesh);
  ASSERT_TRUE(accel.intersect(Ray{{0.5f, 0.0f, 0.0f}, {0, 0, -1}}, &hit));
  EXPECT_EQ(hit.mesh, leaf_mesh);
  EXPECT_FALSE(accel.occluded(Ray{{-0.5f, 0.0f, 0.0f}, {0, 0, -1}, 0.0f, 3.0f}));
  EXPECT_TRUE(accel.occluded(Ray{{0.5f, 0.0f, 0.0f}, {0, 0, -1}, 0.0f, 3.0f}));
}

}  // namespace
}  // namespace phyir::render
