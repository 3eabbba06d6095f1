// The spatially varying lookup: a point between a bright and a dark probe is lit by both.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "insert_test_view.h"
#include "phyir/core/equirect.h"
#include "phyir/core/error.h"
#include "phyir/insert/insert_object.h"
#include "phyir/insert/probe_field.h"

namespace phyir::insert {
namespace {

using namespace testing;

// The left half of the grid (u < 0.5) bright, the right half dark.
glm::vec3 bright_left(int, int j) { return j < 2 ? glm::vec3(10.0f) : glm::vec3(0.1f); }
// The same on a 4 x 8 grid, whose bright and dark centres are closer (u 0.4375 and 0.5625).
glm::vec3 bright_left_8(int, int j) { return j < 4 ? glm::vec3(10.0f) : glm::vec3(0.1f); }

glm::vec3 point_at_u(float u) {
  return kCamera + 2.0f * equirect_direction(glm::vec2(u, 0.5f));
}

TEST(ProbeField, CellCentresReadTheirProbeAndBetweenBlends) {
  const ProbeField field(make_probes(2, 4, bright_left), kCamera);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  // u = 0.375 is column 1's centre (bright), 0.625 column 2's (dark).
  EXPECT_NEAR(field.radiance(point_at_u(0.375f), up).x, 10.0f, 1e-4f);
  EXPECT_NEAR(field.radiance(point_at_u(0.625f), up).x, 0.1f, 1e-4f);
  const float middle = field.radiance(point_at_u(0.5f), up).x;
  EXPECT_NEAR(middle, 0.5f * (10.0f + 0.1f), 1e-3f);
}

TEST(ProbeField, InvalidProbesTakeNoWeight) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);
  probes.mask.at(2, 0) = 0.0f;  // the dark neighbours of the middle
  probes.mask.at(2, 1) = 0.0f;
  const ProbeField field(probes, kCamera);
  EXPECT_NEAR(field.radiance(point_at_u(0.5f), glm::vec3(0, 1, 0)).x, 10.0f, 1e-4f);
}

// Mean green of the object's pixels left and right of the panorama's centre column.
void half_means(const InsertResult& r, float* left, float* right) {
  double sum[2] = {0, 0};
  int n[2] = {0, 0};
  const Image& m = r.composite.mask;
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x)
      if (m.at(x, y) > 0.5f) {
        const int side = x < m.width / 2 ? 0 : 1;
        sum[side] += r.composite.color.at(x, y, 1);
        ++n[side];
      }
  ASSERT_GT(n[0], 0);
  ASSERT_GT(n[1], 0);
  *left = float(sum[0] / n[0]);
  *right = float(sum[1] / n[1]);
}

TEST(ProbeField, ObjectBetweenABrightAndADarkProbeIsLitByBoth) {
  const int width = 128, height = 64;
  const fs::path dir = temp_dir("field");
  write_floor_view(dir, width, height, make_probes(4, 8, bright_left_8));
  const InsertView view = read_insert_view(dir);
  InsertRequest r;
  r.x = width / 2;  // straight ahead, on the boundary between the bright and the dark half
  r.y = int(height * (0.5 + std::atan(0.5) / M_PI));
  r.spp = 32;
  r.lighting.source = "gt";
  float left, right;
  half_means(insert_object(view, box_object(0.5f), r), &left, &right);
  // Its left side takes the bright probes, its right the dark: both light it, unequally.
  EXPECT_GT(left, 1.5f * right);
  EXPECT_GT(right, 0.0f);
  // One global probe lights both halves alike (a symmetric box, the same light everywhere).
  r.lighting.source = "global";
  float gl, gr;
  half_means(insert_object(view, box_object(0.5f), r), &gl, &gr);
  EXPECT_LT(gl / gr, 1.3f);
  EXPECT_GT(gl / gr, 1.0f / 1.3f);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace phyir::insert

namespace phyir::insert {
namespace {

using namespace testing;

// Local mode: probes blended by distance to the vertex in the world, not by projection.
TEST(ProbeField, LocalModeBlendsTheProbesNearTheVertex) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);
  Image positions(4, 2, 3, 0.0f);
  // Only two valid probes, 1 m apart on a floor: the bright one at x = -0.5, the dark at +0.5.
  for (float& m : probes.mask.pixels) m = 0.0f;
  probes.mask.at(1, 1) = 1.0f;  // column 1: bright
  probes.mask.at(2, 1) = 1.0f;  // column 2: dark
  positions.at(1, 1, 0) = -0.5f;
  positions.at(2, 1, 0) = 0.5f;
  ProbeField field(probes, kCamera);
  ASSERT_TRUE(field.use_neighbourhood(positions, glm::vec3(0.0f), 1.0f));
  EXPECT_EQ(field.local_probe_count(), 2u);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const float middle = field.radiance(glm::vec3(0.0f, 0.2f, 0.0f), up).x;
  EXPECT_NEAR(middle, 0.5f * (10.0f + 0.1f), 1e-3f);  // equidistant: lit by both alike
  EXPECT_GT(field.radiance(glm::vec3(-0.4f, 0.1f, 0.0f), up).x, 9.0f);  // beside the bright one
  EXPECT_LT(field.radiance(glm::vec3(0.4f, 0.1f, 0.0f), up).x, 1.1f);   // beside the dark one
  // Nothing within reach: projection mode stays.
  ProbeField far(probes, kCamera);
  EXPECT_FALSE(far.use_neighbourhood(positions, glm::vec3(10.0f, 0.0f, 0.0f), 1.0f));
}

// Support-plane mode: a probe on a wall or on a lower surface near the placement takes no
// weight, one on the support surface's plane does.
TEST(ProbeField, SupportPlaneModeBlendsOnlyTheProbesOnTheSupportPlane) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);
  Image positions(4, 2, 3, 0.0f), normals(4, 2, 3, 0.0f);
  for (float& m : probes.mask.pixels) m = 0.0f;
  // Column 1 (bright): a wall probe 0.3 m away, facing +X. Column 2 (dark): on the table top,
  // 1 cm above its plane y = 0.7. Column 3 (dark): the floor 0.4 m below.
  const glm::vec3 centre(0.0f, 0.7f, 0.0f);
  auto set = [&](int j, glm::vec3 p, glm::vec3 n) {
    probes.mask.at(j, 1) = 1.0f;
    for (int c = 0; c < 3; ++c) positions.at(j, 1, c) = p[c], normals.at(j, 1, c) = n[c];
  };
  set(1, {-0.3f, 0.8f, 0.0f}, {1.0f, 0.0f, 0.0f});
  set(2, {0.2f, 0.71f, 0.0f}, {0.0f, 1.0f, 0.0f});
  set(3, {0.0f, 0.31f, 0.2f}, {0.0f, 1.0f, 0.0f});
  ProbeField all(probes, kCamera), plane(probes, kCamera);
  ASSERT_TRUE(all.use_neighbourhood(positions, centre, 1.0f));
  EXPECT_EQ(all.local_probe_count(), 3u);
  ASSERT_TRUE(plane.use_neighbourhood(positions, centre, 1.0f, {&normals, glm::vec3(0.0f, 1.0f, 0.0f)}));
  EXPECT_EQ(plane.local_probe_count(), 1u);
  const glm::vec3 up(0.0f, 1.0f, 0.0f), vertex(-0.1f, 0.8f, 0.0f);
  EXPECT_GT(all.radiance(vertex, up).x, 1.0f);             // the wall's bright probe takes weight
  EXPECT_NEAR(plane.radiance(vertex, up).x, 0.1f, 1e-5f);  // only the table top's
  // Normals of another size than the grid: an error naming the file.
  const Image small(2, 1, 3);
  try {
    plane.use_neighbourhood(positions, centre, 1.0f, {&small, up});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("probe_normal.exr"));
  }
}

// A higher blend power makes the nearest probe dominate; equidistant probes still share alike.
TEST(ProbeField, HigherBlendPowerFavoursTheNearestProbe) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);
  Image positions(4, 2, 3, 0.0f);
  for (float& m : probes.mask.pixels) m = 0.0f;
  probes.mask.at(1, 1) = 1.0f, probes.mask.at(2, 1) = 1.0f;
  positions.at(1, 1, 0) = -0.5f, positions.at(2, 1, 0) = 0.5f;
  ProbeField two(probes, kCamera), four(probes, kCamera);
  ASSERT_TRUE(two.use_neighbourhood(positions, glm::vec3(0.0f), 1.0f));
  ASSERT_TRUE(four.use_neighbourhood(positions, glm::vec3(0.0f), 1.0f));
  four.set_blend_power(4.0f);
  const glm::vec3 up(0.0f, 1.0f, 0.0f), near_bright(-0.2f, 0.1f, 0.0f);
  // Squared distances 0.1025 and 0.5025 (with the 5 cm smoothing): weights 4.9 : 1 and 24 : 1.
  const float w2 = 0.5025f / 0.1025f, w4 = w2 * w2;
  EXPECT_NEAR(two.radiance(near_bright, up).x, (w2 * 10.0f + 0.1f) / (w2 + 1.0f), 1e-3f);
  EXPECT_NEAR(four.radiance(near_bright, up).x, (w4 * 10.0f + 0.1f) / (w4 + 1.0f), 1e-3f);
  EXPECT_NEAR(four.radiance(glm::vec3(0.0f, 0.2f, 0.0f), up).x, 0.5f * (10.0f + 0.1f), 1e-3f);
  EXPECT_THROW(four.set_blend_power(0.0f), Error);
}

// With a blend plane, a vertex high above a probe takes that probe as if it stood on it.
TEST(ProbeField, BlendPlaneMeasuresDistancesBetweenFootPoints) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);
  Image positions(4, 2, 3, 0.0f);
  for (float& m : probes.mask.pixels) m = 0.0f;
  probes.mask.at(1, 1) = 1.0f, probes.mask.at(2, 1) = 1.0f;
  positions.at(1, 1, 0) = 0.0f, positions.at(2, 1, 0) = 0.4f;  // bright under the vertex, dark 0.4 m off
  ProbeField in3d(probes, kCamera), foot(probes, kCamera);
  ASSERT_TRUE(in3d.use_neighbourhood(positions, glm::vec3(0.0f), 1.0f));
  ASSERT_TRUE(foot.use_neighbourhood(positions, glm::vec3(0.0f), 1.0f));
  foot.set_blend_plane(glm::vec3(0.0f, 1.0f, 0.0f));
  const glm::vec3 up(0.0f, 1.0f, 0.0f), high(0.0f, 0.3f, 0.0f);
  // In 3D: squared distances 0.09 and 0.25 (+ 0.0025), tapers 1 and 0.7056: the dark probe
  // takes a fifth.
  const float bright3d = 1.0f / 0.0925f, dark3d = 0.7056f / 0.2525f;
  EXPECT_NEAR(in3d.radiance(high, up).x, (bright3d * 10.0f + dark3d * 0.1f) / (bright3d + dark3d), 1e-3f);
  // Foot points: 0 and 0.16 (+ 0.0025): weights 65 : 1, times the tapers of the probes'
  // distances to the centre, 1 and (1 - 0.4^2)^2.
  const float w = 0.1625f / 0.0025f / ((1.0f - 0.16f) * (1.0f - 0.16f));
  EXPECT_NEAR(foot.radiance(high, up).x, (w * 10.0f + 0.1f) / (w + 1.0f), 1e-3f);
  EXPECT_THROW(foot.set_blend_plane(glm::vec3(0.0f, 2.0f, 0.0f)), Error);
}

// Bright and dark probes alternating every 2 cm along a line: more than the cap within reach.
glm::vec3 striped(int, int j) { return j % 2 ? glm::vec3(10.0f) : glm::vec3(0.1f); }

// Moving the centre in 1 mm steps along the line (the vertex still), probes enter and leave the
// set at its edge (the radius, and the cap of kMaxLocalProbes) with zero weight: no step jumps.
TEST(ProbeField, BlendChangesContinuouslyAsTheCentreMoves) {
  const int n = 200;
  view::ProbeMosaic probes = make_probes(1, n, striped);
  Image positions(n, 1, 3, 0.0f);
  for (int j = 0; j < n; ++j) positions.at(j, 0, 0) = 0.02f * float(j);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  float previous = -1.0f, largest_step = 0.0f;
  for (int step = 0; step <= 400; ++step) {
    const glm::vec3 centre(1.0f + 0.001f * float(step), 0.0f, 0.0f);
    ProbeField field(probes, kCamera);
    ASSERT_TRUE(field.use_neighbourhood(positions, centre, 0.8f));
    ASSERT_LE(field.local_probe_count(), kMaxLocalProbes);
    const float r = field.radiance(glm::vec3(1.2f, 0.3f, 0.0f), up).x;
    if (previous >= 0.0f) largest_step = std::max(largest_step, std::abs(r - previous));
    previous = r;
  }
  // Untapered, a probe entering or leaving at the edge makes the blend jump by 0.05 here.
  EXPECT_LT(largest_step, 0.005f) << largest_step;
}

// With ray distances a probe on the line through the vertex along the direction looked up
// takes the weight, whatever its distance to the vertex: the probe under the vertex looking
// up, the one level with it looking sideways.
TEST(ProbeField, RayDistanceFavoursTheProbeOnTheRayThroughTheVertex) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);
  Image positions(4, 2, 3, 0.0f);
  for (float& m : probes.mask.pixels) m = 0.0f;
  probes.mask.at(1, 1) = 1.0f, probes.mask.at(2, 1) = 1.0f;
  // Bright at the origin, 0.3 m under the vertex; dark 0.2 m beside the vertex, level with it.
  positions.at(2, 1, 0) = 0.2f, positions.at(2, 1, 1) = 0.3f;
  ProbeField field(probes, kCamera);
  ASSERT_TRUE(field.use_neighbourhood(positions, glm::vec3(0.0f), 1.0f));
  field.set_ray_distance(true);
  const glm::vec3 vertex(0.0f, 0.3f, 0.0f);
  const float s2 = kLocalSmoothing * kLocalSmoothing, dark_taper = (1.0f - 0.13f) * (1.0f - 0.13f);
  // Up: across-ray offsets 0 (bright) and 0.2 m (dark).
  const float bright_up = 1.0f / s2, dark_up = dark_taper / (0.04f + s2);
  EXPECT_NEAR(field.radiance(vertex, glm::vec3(0, 1, 0)).x, (bright_up * 10.0f + dark_up * 0.1f) / (bright_up + dark_up),
              1e-3f);
  // Sideways (+X): 0.3 m (bright) and 0 (dark).
  const float bright_side = 1.0f / (0.09f + s2), dark_side = dark_taper / s2;
  EXPECT_NEAR(field.radiance(vertex, glm::vec3(1, 0, 0)).x,
              (bright_side * 10.0f + dark_side * 0.1f) / (bright_side + dark_side), 1e-3f);
  EXPECT_THROW(field.set_blend_plane(glm::vec3(0, 1, 0)), Error);
}

// A table top at y = 0.7 and the floor under it: the floor's probe, on the line through the
// vertex, lights the vertex's downward rays (it is where they go) but not its upward ones (it
// would see them through the table top).
TEST(ProbeField, RayDistanceKeepsProbesBehindTheSupportSurfaceOutOfItsRays) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);
  Image positions(4, 2, 3, 0.0f);
  for (float& m : probes.mask.pixels) m = 0.0f;
  probes.mask.at(1, 1) = 1.0f, probes.mask.at(2, 1) = 1.0f;
  positions.at(1, 1, 1) = 0.01f;                           // bright: the floor, under the vertex
  positions.at(2, 1, 0) = 0.3f, positions.at(2, 1, 1) = 0.71f;  // dark: the table top, 0.3 m aside
  const glm::vec3 centre(0.0f, 0.7f, 0.0f), up(0.0f, 1.0f, 0.0f), vertex(0.0f, 0.85f, 0.0f);
  ProbeField field(probes, kCamera);
  ASSERT_TRUE(field.use_neighbourhood(positions, centre, 1.0f));
  field.set_ray_distance(true);
  EXPECT_GT(field.radiance(vertex, up).x, 5.0f);  // no plane: the floor's probe is on the upward ray
  field.set_support_plane(centre, up);
  EXPECT_NEAR(field.radiance(vertex, up).x, 0.1f, 1e-5f);      // only the table top's
  EXPECT_GT(field.radiance(vertex, -up).x, 5.0f);              // down: the floor's again
  EXPECT_THROW(field.set_support_plane(centre, 2.0f * up), Error);
}

// The local blend's sampling map is the taper-weighted mean of its probes' images: bright
// wherever any of them sees light.
TEST(ProbeField, SamplingMapIsTheTaperedMeanOfTheLocalProbes) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);
  Image positions(4, 2, 3, 0.0f);
  for (float& m : probes.mask.pixels) m = 0.0f;
  probes.mask.at(1, 1) = 1.0f, probes.mask.at(2, 1) = 1.0f;  // bright at the centre, dark 0.5 m off
  positions.at(2, 1, 0) = 0.5f;
  ProbeField field(probes, kCamera);
  EXPECT_TRUE(field.local_sampling_map().empty());  // no local blend yet
  ASSERT_TRUE(field.use_neighbourhood(positions, glm::vec3(0.0f), 1.0f));
  const Image map = field.local_sampling_map();
  ASSERT_EQ(map.width, probes.layout.res_width);
  ASSERT_EQ(map.height, probes.layout.res_height);
  const float dark_taper = (1.0f - 0.25f) * (1.0f - 0.25f);
  const float expected = (10.0f + dark_taper * 0.1f) / (1.0f + dark_taper);
  for (float v : map.pixels) EXPECT_NEAR(v, expected, 1e-4f);
}

// The constant baseline: the solid-angle weighted mean over the valid probes only.
TEST(ProbeField, MeanRadianceIsOverTheValidProbesOnly) {
  view::ProbeMosaic probes = make_probes(2, 4, bright_left);  // columns 0-1: 10, columns 2-3: 0.1
  for (float& m : probes.mask.pixels) m = 0.0f;
  probes.mask.at(0, 0) = 1.0f, probes.mask.at(3, 1) = 1.0f;  // one bright and one dim probe
  const glm::vec3 mean = mean_probe_radiance(probes);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mean[k], 0.5f * (10.0f + 0.1f), 1e-4f);
  for (float& m : probes.mask.pixels) m = 0.0f;
  EXPECT_THROW(mean_probe_radiance(probes), Error);
}

}  // namespace
}  // namespace phyir::insert
