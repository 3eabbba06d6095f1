// The light portals a scene declares in its extras.phyir.portals: read in world space, and
// every malformed entry refused naming the file, the scene, the entry and the problem. The
// apartment generator writes its windows as portals facing into the rooms.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::GltfBuilder;
using ::testing::AllOf;
using ::testing::HasSubstr;

fs::path scene_with_portals(const fs::path& dir, const json& portals) {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2});
  b.set_scene({b.add_node({{"mesh", 0}})});
  b.doc["scenes"][0]["extras"] = {{"phyir", {{"portals", portals}}}};
  return b.write_gltf(dir, "room");
}

std::string load_error(const fs::path& path) {
  try {
    load_gltf(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GltfPortals, ReadInWorldSpace) {
  const fs::path dir = test::fresh_test_dir();
  const Scene scene = load_gltf(
      scene_with_portals(dir, json::array({{{"corner", {2, 1, -0.5}}, {"edge_u", {0, 0, 1}}, {"edge_v", {0, 1.2, 0}}}})));
  ASSERT_EQ(scene.portals.size(), 1u);
  EXPECT_EQ(scene.portals[0].corner, glm::vec3(2.0f, 1.0f, -0.5f));
  EXPECT_EQ(scene.portals[0].edge_v, glm::vec3(0.0f, 1.2f, 0.0f));
}

TEST(GltfPortals, MalformedEntriesAreRefused) {
  const fs::path dir = test::fresh_test_dir();
  const json good = {{"corner", {0, 0, 0}}, {"edge_u", {1, 0, 0}}, {"edge_v", {0, 1, 0}}};
  EXPECT_THAT(load_error(scene_with_portals(dir, good)), HasSubstr("not an array"));
  EXPECT_THAT(load_error(scene_with_portals(dir, json::array({1}))), HasSubstr("entry 0 is not an object"));
  json missing = good;
  missing.erase("edge_v");
  EXPECT_THAT(load_error(scene_with_portals(dir, json::array({good, missing}))),
              AllOf(HasSubstr("room.gltf"), HasSubstr("extras.phyir.portals entry 1"), HasSubstr("'edge_v'")));
  json parallel = good;
  parallel["edge_v"] = {2, 0, 0};
  EXPECT_THAT(load_error(scene_with_portals(dir, json::array({parallel}))), HasSubstr("no area"));
  json unknown = good;
  unknown["normal"] = {0, 0, 1};
  EXPECT_THAT(load_error(scene_with_portals(dir, json::array({unknown}))), HasSubstr("unknown member 'normal'"));
}

}  // namespace
}  // namespace phyir::scenes
