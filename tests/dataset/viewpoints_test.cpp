// Viewpoints: the scene's own first, then free-space samples that obey the rules, checked
// with independent geometry (exact point-to-triangle distances, the room plan's floor
// polygon), deterministic per seed, and a longer plan extends a shorter one.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "dataset_test_helpers.h"
#include "phyir/core/closest_point.h"
#include "phyir/core/error.h"
#include "phyir/dataset/viewpoints.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/room_layout.h"

namespace phyir::dataset {
namespace {

using ::testing::HasSubstr;

float distance_to_scene(const scenes::Scene& scene, const glm::vec3& p) {
  float best = std::numeric_limits<float>::infinity();
  for (const scenes::Mesh& m : scene.meshes)
    for (const glm::uvec3& t : m.triangles)
      best = std::min(best, glm::distance(p, closest_point_on_triangle(p, m.positions[t.x], m.positions[t.y], m.positions[t.z])));
  return best;
}

struct Room {
  scenes::Scene scene;
  scenes::RoomLayout layout;
};

Room load_room(const std::filesystem::path& dir, int index, scenes::RoomPreset preset, uint64_t seed) {
  scenes::generate_room(dir, index, seed, preset);
  return {scenes::load_gltf(dir / ("room_" + std::to_string(index) + ".gltf")), scenes::plan_room(seed, index, preset)};
}

TEST(Viewpoints, SceneViewpointsComeFirstInFileOrder) {
  const auto dir = test::fresh_test_dir();
  const Room room = load_room(dir, 0, scenes::RoomPreset::Mini, 1);
  const int authored = int(room.scene.cameras.size() + room.scene.candidate_viewpoints.size());
  ASSERT_GE(authored, 9);
  const auto views = plan_viewpoints(room.scene, "room_0", 4, 1, ViewpointRules{});
  ASSERT_EQ(views.size(), 4u);
  EXPECT_EQ(views[0].source, ViewpointSource::Camera);
  EXPECT_EQ(views[0].position, room.scene.cameras[0].position);
  for (int i = 1; i < 4; ++i) {
    EXPECT_EQ(views[i].source, ViewpointSource::Candidate);
    EXPECT_EQ(views[i].source_index, i - 1);
    EXPECT_EQ(views[i].position, room.scene.candidate_viewpoints[size_t(i - 1)]);
  }
}

TEST(Viewpoints, SampledPointsKeepClearHeightAndRoom) {
  const auto dir = test::fresh_test_dir();
  const ViewpointRules rules;
  int sampled = 0;
  // A mini room and two hard ones (thin geometry, small lights, mirrors, glass): the first
  // L-shaped one (its notch is inside the bounds but outside the room) and a rectangular one.
  int l_shaped = -1, rectangular = -1;
  for (int i = 0; i < 20; ++i) {
    const bool l = scenes::plan_room(7, i, scenes::RoomPreset::Hard).shell.l_shaped;
    if (l && l_shaped < 0) l_shaped = i;
    if (!l && rectangular < 0) rectangular = i;
  }
  ASSERT_GE(l_shaped, 0);
  ASSERT_GE(rectangular, 0);
  for (const auto& [preset, index] : {std::pair{scenes::RoomPreset::Mini, 0}, std::pair{scenes::RoomPreset::Hard, l_shaped},
                                      std::pair{scenes::RoomPreset::Hard, rectangular}}) {
    const Room room = load_room(dir, index, preset, 7);
    if (room.layout.shell.l_shaped) {  // the notch: inside the bounds, outside the walls
      const glm::vec2 c = 0.5f * (room.layout.shell.notch_min + room.layout.shell.notch_max);
      const render::Accelerator accel(room.scene);
      ClearanceProbe probe;
      EXPECT_FALSE(is_free_viewpoint(room.scene, accel, glm::vec3(c.x, 1.5f, c.y), rules, &probe));
      EXPECT_GT(probe.back_faces, 0);
    }
    const int authored = int(room.scene.cameras.size() + room.scene.candidate_viewpoints.size());
    const auto views = plan_viewpoints(room.scene, "room", authored + 6, 7, rules);
    ASSERT_EQ(int(views.size()), authored + 6);
    for (const Viewpoint& v : views) {
      if (v.source != ViewpointSource::Sampled) continue;
      ++sampled;
      const glm::vec3 p = v.position;
      SCOPED_TRACE(::testing::Message() << "room " << index << " point " << p.x << "," << p.y << "," << p.z);
      EXPECT_GE(p.y, 1.2f - 1e-4f);
      EXPECT_LE(p.y, 1.8f + 1e-4f);
      // On the millimetre grid.
      for (float c : {p.x, p.y, p.z}) EXPECT_NEAR(c * 1000.0f, std::round(c * 1000.0f), 1e-2f);
      // Inside the floor polygon with the clearance to every wall (the plan's own polygon).
      EXPECT_TRUE(room.layout.shell.contains(glm::vec2(p.x, p.z), rules.clearance - 0.01f));
      // Exact distance to every triangle: the rays sample directions, so allow a little less.
      EXPECT_GE(distance_to_scene(room.scene, p), 0.8f * rules.clearance);
      EXPECT_GE(v.clearance, rules.clearance);
      for (const Viewpoint& other : views)
        if (&other != &v) {
          EXPECT_GE(glm::distance(p, other.position), 0.5f * rules.min_spacing - 1e-4f);
        }
    }
  }
  EXPECT_EQ(sampled, 18);
}

TEST(Viewpoints, DeterministicPerSeedAndPrefixStable) {
  const auto dir = test::fresh_test_dir();
  const Room room = load_room(dir, 0, scenes::RoomPreset::Mini, 3);
  const int authored = int(room.scene.cameras.size() + room.scene.candidate_viewpoints.size());
  const ViewpointRules rules;
  const auto a = plan_viewpoints(room.scene, "room_0", authored + 4, 11, rules);
  const auto b = plan_viewpoints(room.scene, "room_0", authored + 4, 11, rules);
  const auto longer = plan_viewpoints(room.scene, "room_0", authored + 6, 11, rules);
  const auto other_seed = plan_viewpoints(room.scene, "room_0", authored + 4, 12, rules);
  const auto other_name = plan_viewpoints(room.scene, "room_9", authored + 4, 11, rules);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position);
    EXPECT_EQ(a[i].position, longer[i].position);
  }
  EXPECT_NE(a.back().position, other_seed.back().position);
  EXPECT_NE(a.back().position, other_name.back().position);
  EXPECT_EQ(a[size_t(authored) - 1].position, other_seed[size_t(authored) - 1].position);  // authored ones do not move
}

TEST(Viewpoints, ClearanceProbeSeesInsideSolidsAndOutsideWalls) {
  const auto dir = test::fresh_test_dir();
  const Room room = load_room(dir, 0, scenes::RoomPreset::Mini, 1);
  const render::Accelerator accel(room.scene);
  const ViewpointRules rules;
  // The generator placed its camera by the same rules (with boxes instead of rays).
  EXPECT_TRUE(is_free_viewpoint(room.scene, accel, room.scene.cameras[0].position, rules));
  // Inside the first floor object's box: back faces (or far too close).
  const scenes::RoomObject* table = nullptr;
  for (const auto& o : room.layout.objects)
    if (o.mount == scenes::Mount::Floor) table = &o;
  ASSERT_NE(table, nullptr);
  const glm::vec3 inside = table->parts[0].bounds.centre();
  const ClearanceProbe in_box = probe_clearance(room.scene, accel, inside, 64);
  EXPECT_GT(in_box.back_faces, 0);
  // Outside the room, looking at the walls' backs.
  const glm::vec3 outside(room.layout.shell.width, 1.5f, 0.0f);
  const ClearanceProbe out = probe_clearance(room.scene, accel, outside, 64);
  EXPECT_GT(out.back_faces, 0);
}

TEST(Viewpoints, TooCrowdedFailsNamingTheScene) {
  const auto dir = test::fresh_test_dir();
  const Room room = load_room(dir, 0, scenes::RoomPreset::Mini, 1);
  ViewpointRules rules;
  rules.clearance = 5.0f;  // wider than any mini room
  rules.attempts = 50;
  const int authored = int(room.scene.cameras.size() + room.scene.candidate_viewpoints.size());
  try {
    plan_viewpoints(room.scene, "room_0", authored + 1, 1, rules);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("room_0"));
  }
}

}  // namespace
}  // namespace phyir::dataset
