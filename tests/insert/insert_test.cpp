// phyir insert: placement, the differential composite, the spatially varying lookup, bad input.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstring>

#include "insert_test_view.h"
#include "phyir/core/error.h"
#include "phyir/insert/insert_object.h"
#include "phyir/insert/probe_field.h"

namespace phyir::insert {
namespace {

using namespace testing;

constexpr int kWidth = 64, kHeight = 32;

// The floor pixel straight ahead (-Z), 2 m away: the camera is 1 m up, so 26.6 degrees down.
void ahead_pixel(int* x, int* y) {
  *x = kWidth / 2;
  *y = int(kHeight * (0.5 + std::atan(0.5) / M_PI));
}

InsertRequest request_at(int x, int y, const std::string& lighting) {
  InsertRequest r;
  r.x = x, r.y = y;
  r.lighting.source = lighting;
  r.spp = 16;
  r.seed = 3;
  return r;
}

TEST(InsertPlacement, StandsOnThePixelsWorldPoint) {
  const fs::path dir = temp_dir("placement");
  write_floor_view(dir, kWidth, kHeight, make_probes(kHeight / 4, kWidth / 4, uniform_light));
  const InsertView view = read_insert_view(dir);
  int x, y;
  ahead_pixel(&x, &y);
  const SurfacePoint ground = surface_at(view, x, y);
  // The pixel centre's ray meets the floor at y = 0, straight ahead.
  const glm::vec3 d = equirect_direction(glm::vec2((x + 0.5f) / kWidth, (y + 0.5f) / kHeight));
  const glm::vec3 expected = kCamera + d * (kCamera.y / -d.y);
  EXPECT_NEAR(ground.position.y, 0.0f, 1e-4f);
  EXPECT_NEAR(ground.position.x, expected.x, 1e-4f);
  EXPECT_NEAR(ground.position.z, expected.z, 1e-4f);
  EXPECT_LT(ground.position.z, -1.0f);
  Placement p;
  p.scale = 2.0f;
  const scenes::Scene placed = place_object(box_object(0.1f), ground, p);
  const scenes::Bounds b = placed.compute_bounds();
  EXPECT_NEAR(0.5f * (b.min.x + b.max.x), ground.position.x, 1e-5f);
  EXPECT_NEAR(0.5f * (b.min.z + b.max.z), ground.position.z, 1e-5f);
  EXPECT_NEAR(b.min.y, ground.position.y, 1e-3f);  // resting on it, lifted 0.5 mm
  EXPECT_NEAR(b.max.y - b.min.y, 0.4f, 1e-5f);     // scaled
  fs::remove_all(dir);
}

TEST(InsertComposite, ZeroSizeObjectLeavesTheBackgroundByteIdentical) {
  const fs::path dir = temp_dir("zero");
  write_floor_view(dir, kWidth, kHeight, make_probes(kHeight / 4, kWidth / 4, uniform_light));
  const InsertView view = read_insert_view(dir);
  int x, y;
  ahead_pixel(&x, &y);
  InsertRequest r = request_at(x, y, "gt");
  r.placement.scale = 0.0f;
  const InsertResult result = insert_object(view, box_object(0.2f), r);
  ASSERT_EQ(result.composite.color.pixels.size(), view.color.pixels.size());
  EXPECT_EQ(0, std::memcmp(result.composite.color.pixels.data(), view.color.pixels.data(),
                           view.color.pixels.size() * sizeof(float)));
  for (float m : result.composite.mask.pixels) EXPECT_EQ(m, 0.0f);
  // And a real object does change it (the test can fail).
  r.placement.scale = 1.0f;
  const InsertResult real = insert_object(view, box_object(0.2f), r);
  EXPECT_NE(0, std::memcmp(real.composite.color.pixels.data(), view.color.pixels.data(),
                           view.color.pixels.size() * sizeof(float)));
  fs::remove_all(dir);
}

TEST(InsertComposite, ObjectCastsAShadowOnItsSurface) {
  const fs::path dir = temp_dir("shadow");
  write_floor_view(dir, kWidth, kHeight, make_probes(kHeight / 4, kWidth / 4, uniform_light));
  const InsertView view = read_insert_view(dir);
  int x, y;
  ahead_pixel(&x, &y);
  InsertRequest r = request_at(x, y, "gt");
  r.spp = 64;
  const InsertResult result = insert_object(view, box_object(0.15f), r);
  // Floor pixels just below the object's mask, beside its foot, darker than the background.
  int darker = 0, floor_pixels = 0;
  for (int py = 0; py < kHeight; ++py)
    for (int px = 0; px < kWidth; ++px) {
      if (result.composite.mask.at(px, py) > 0.5f || result.without_object.mask.at(px, py) < 0.5f) continue;
      ++floor_pixels;
      if (result.composite.color.at(px, py, 1) < view.color.at(px, py, 1) - 1e-3f) ++darker;
    }
  EXPECT_GT(floor_pixels, 0);
  EXPECT_GT(darker, 0);
  fs::remove_all(dir);
}

TEST(InsertComposite, SameSeedSameCompositeWhateverTheThreadCount) {
  const fs::path dir = temp_dir("threads");
  write_floor_view(dir, kWidth, kHeight, make_probes(kHeight / 4, kWidth / 4, uniform_light));
  const InsertView view = read_insert_view(dir);
  int x, y;
  ahead_pixel(&x, &y);
  const InsertRequest r = request_at(x, y, "gt");
  Image one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = insert_object(view, box_object(0.2f), r).composite.color;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = insert_object(view, box_object(0.2f), r).composite.color;
  }
  EXPECT_EQ(one.pixels, two.pixels);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace phyir::insert

namespace phyir::insert {
namespace {

// A disc overhanging the view's surface (a table's edge, the floor 2 m farther) changes nothing.
// Normals all +Y (a floor or a table top), `n` pixels wide.
Image up_normals(int n) {
  Image normals(n, 1, 3, 0.0f);
  for (int x = 0; x < n; ++x) normals.at(x, 0, 1) = 1.0f;
  return normals;
}

TEST(InsertComposite, OverhangingSupportSurfaceLeavesTheBackground) {
  Image background(2, 1, 3, 0.5f), view_depth(2, 1, 1, 1.0f);
  view_depth.at(1, 0) = 3.0f;  // pixel 1: the floor below the table's edge
  LocalRender with{Image(2, 1, 3, 0.1f), Image(2, 1, 1, 1.0f), Image(2, 1, 1, 1.0f)};
  LocalRender without{Image(2, 1, 3, 0.3f), Image(2, 1, 1, 1.0f), Image(2, 1, 1, 1.0f)};
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const Composite c = differential_composite(background, view_depth, up_normals(2), up, with, without);
  EXPECT_NEAR(c.color.at(0, 0, 0), 0.5f * 0.1f / 0.3f, 1e-6f);  // on the table: the shadow
  EXPECT_EQ(c.color.at(1, 0, 0), 0.5f);                         // past its edge: untouched
  EXPECT_EQ(c.mask.at(0, 0), 0.0f);
}

// A table's front face at the disc's depth (its top edge) is not the support surface.
TEST(InsertComposite, SurfaceFacingAnotherWayLeavesTheBackground) {
  Image background(1, 1, 3, 0.5f), view_depth(1, 1, 1, 1.0f), normals(1, 1, 3, 0.0f);
  normals.at(0, 0, 2) = -1.0f;
  LocalRender with{Image(1, 1, 3, 0.1f), Image(1, 1, 1, 1.0f), Image(1, 1, 1, 1.0f)};
  LocalRender without{Image(1, 1, 3, 0.3f), Image(1, 1, 1, 1.0f), Image(1, 1, 1, 1.0f)};
  const Composite c = differential_composite(background, view_depth, normals, glm::vec3(0, 1, 0), with, without);
  EXPECT_EQ(c.color.at(0, 0, 0), 0.5f);
}

// The shadow keeps its fraction on a pixel darker than the disc alone (the difference would
// take it below zero), and where the disc alone is black the object's light is added.
TEST(InsertComposite, ShadowIsTheSurfacesCalibratedFraction) {
  Image background(2, 1, 3, 0.05f), view_depth(2, 1, 1, 1.0f);
  LocalRender with{Image(2, 1, 3, 0.1f), Image(2, 1, 1, 1.0f), Image(2, 1, 1, 1.0f)};
  LocalRender without{Image(2, 1, 3, 0.3f), Image(2, 1, 1, 1.0f), Image(2, 1, 1, 1.0f)};
  for (int c = 0; c < 3; ++c) without.color.at(1, 0, c) = 0.0f;
  const Composite c = differential_composite(background, view_depth, up_normals(2), glm::vec3(0, 1, 0), with, without);
  EXPECT_NEAR(c.color.at(0, 0, 0), 0.05f / 3.0f, 1e-6f);
  EXPECT_NEAR(c.color.at(1, 0, 0), 0.05f + 0.1f, 1e-6f);
}

}  // namespace
}  // namespace phyir::insert
