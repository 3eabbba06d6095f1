// KHR_lights_punctual in the loader: lights on nodes anywhere in the hierarchy, placed by
// the node transforms (spot and directional lights along the node's -Z), photometric units
// kept and converted at 683 lm/W, the spot cone's falloff, and malformed lights refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/scene_info.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using ::testing::AllOf;
using ::testing::HasSubstr;
using Type = PunctualLight::Type;

constexpr double kHalfPi = 1.5707963267948966;

// A triangle plus three lights: a point light on a child of a translated parent, a spot on
// a node turned -90 degrees about +X (its -Z then points down, -Y), and a sun on a node
// turned about +Y (its -Z then points along -X).
GltfBuilder lit_builder() {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2});
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensionsRequired"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array(
      {{{"name", "lamp"}, {"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 683.0}, {"range", 7.0}},
       {{"name", "spot"}, {"type", "spot"}, {"intensity", 1366.0},
        {"spot", {{"innerConeAngle", 0.3}, {"outerConeAngle", 0.6}}}},
       {{"name", "sun"}, {"type", "directional"}, {"intensity", 6830.0}}});
  const double s = std::sqrt(0.5);
  const int lamp = b.add_node({{"translation", {0.0, 1.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const int parent = b.add_node({{"translation", {1.0, 2.0, 3.0}}, {"scale", {2.0, 2.0, 2.0}}, {"children", {lamp}}});
  const int spot = b.add_node({{"rotation", {-s, 0.0, 0.0, s}}, {"translation", {0.0, 2.5, 0.0}},
                               {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  const int sun = b.add_node({{"rotation", {0.0, s, 0.0, s}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  b.set_scene({b.add_node({{"mesh", 0}}), parent, spot, sun});
  return b;
}

void expect_near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << "component " << i;
}

TEST(GltfLights, LightsArePlacedByTheirNodes) {
  const Scene scene = load_gltf(lit_builder().write_gltf(test::fresh_test_dir(), "lit"));
  ASSERT_EQ(scene.lights.size(), 3u);
  EXPECT_EQ(scene.info.lights, 3);
  const PunctualLight& lamp = scene.lights[0];
  EXPECT_EQ(lamp.type, Type::Point);
  EXPECT_EQ(lamp.name, "lamp");
  expect_near(lamp.position, glm::vec3(1.0f, 4.0f, 3.0f));  // parent translation + 2 x child's
  EXPECT_EQ(lamp.range, 7.0f);
  const PunctualLight& spot = scene.lights[1];
  expect_near(spot.position, glm::vec3(0.0f, 2.5f, 0.0f));
  expect_near(spot.direction, glm::vec3(0.0f, -1.0f, 0.0f));
  EXPECT_FLOAT_EQ(spot.inner_cone_angle, 0.3f);
  EXPECT_FLOAT_EQ(spot.outer_cone_angle, 0.6f);
  expect_near(scene.lights[2].direction, glm::vec3(-1.0f, 0.0f, 0.0f));
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
}

TEST(GltfLights, PhotometricUnitsBecomeRadiometricAt683LumensPerWatt) {
  const Scene scene = load_gltf(lit_builder().write_gltf(test::fresh_test_dir(), "lit"));
  expect_near(scene.lights[0].radiometric(), glm::vec3(1.0f, 0.5f, 0.25f));  // 683 cd x colour -> W/sr
  expect_near(scene.lights[1].radiometric(), glm::vec3(2.0f));
  expect_near(scene.lights[2].radiometric(), glm::vec3(10.0f));               // 6830 lx -> W/m^2
  const std::string info = scene_info_text(scene);
  EXPECT_THAT(info, HasSubstr("6830 lx x colour (1, 1, 1) = 10 W/m^2"));
  EXPECT_THAT(info, HasSubstr("1366 cd x colour (1, 1, 1) = 2 W/sr"));
  EXPECT_EQ(scene_info_json(scene)["lights"][2]["intensity_unit"], "lx");
}

TEST(GltfLights, SpotFalloffFollowsTheExtensionsRamp) {
  PunctualLight spot;
  spot.type = Type::Spot;
  spot.inner_cone_angle = 0.3f;
  spot.outer_cone_angle = 0.6f;
  EXPECT_FLOAT_EQ(spot.spot_falloff(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(spot.spot_falloff(std::cos(0.3f)), 1.0f);
  EXPECT_NEAR(spot.spot_falloff(std::cos(0.6f)), 0.0f, 1e-6f);
  EXPECT_EQ(spot.spot_falloff(std::cos(0.7f)), 0.0f);
  const float c = 0.5f * (std::cos(0.3f) + std::cos(0.6f));  // halfway in cosine: (1/2)^2
  EXPECT_NEAR(spot.spot_falloff(c), 0.25f, 1e-5f);
  spot.inner_cone_angle = spot.outer_cone_angle;  // a hard edge, no division by zero
  EXPECT_FLOAT_EQ(spot.spot_falloff(std::cos(0.59f)), 1.0f);
  EXPECT_EQ(spot.spot_falloff(std::cos(0.61f)), 0.0f);
}

TEST(GltfLights, ALightUsedByTwoNodesIsTwoLights) {
  GltfBuilder b = lit_builder();
  b.doc["nodes"].push_back({{"translation", {5.0, 0.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.doc["scenes"][0]["nodes"].push_back(b.doc["nodes"].size() - 1);
  const Scene scene = load_gltf(b.write_gltf(test::fresh_test_dir(), "lit"));
  ASSERT_EQ(scene.lights.size(), 4u);
  expect_near(scene.lights[3].position, glm::vec3(5.0f, 0.0f, 0.0f));
}

std::string load_error(GltfBuilder b) {
  try {
    load_gltf(b.write_gltf(test::fresh_test_dir(), "bad"));
  } catch (const Error& e) {
    return e.what();
  }
  return "(loaded)";
}

TEST(GltfLights, MalformedLightsAreRefusedNamingTheLight) {
  auto broken = [](auto edit) {
    GltfBuilder b = lit_builder();
    edit(b.doc);
    return load_error(b);
  };
  auto L = [](json& doc) -> json& { return doc["extensions"]["KHR_lights_punctual"]["lights"]; };
  // The schema check (gltf_schema.cpp) or the light reader refuses each; either names the
  // light and the property.
  auto names = [](const char* light, const char* property) { return AllOf(HasSubstr(light), HasSubstr(property)); };
  EXPECT_THAT(broken([&](json& d) { L(d)[0]["type"] = "laser"; }), names("'lamp'", "laser"));
  EXPECT_THAT(broken([&](json& d) { L(d)[0]["intensity"] = -1.0; }), names("'lamp'", "intensity is -1"));
  EXPECT_THAT(broken([&](json& d) { L(d)[0]["color"] = {1.0, 2.0, 0.0}; }), names("'lamp'", "color[1] is 2"));
  EXPECT_THAT(broken([&](json& d) { L(d)[1]["spot"]["outerConeAngle"] = 2.0; }), names("'spot'", "outerConeAngle is 2"));
  EXPECT_THAT(broken([&](json& d) { L(d)[1]["spot"]["innerConeAngle"] = kHalfPi; }), names("'spot'", "innerConeAngle is"));
  EXPECT_THAT(broken([&](json& d) { L(d)[1]["spot"] = {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.4}}; }),
              names("'spot'", "outerConeAngle"));
  EXPECT_THAT(broken([](json& d) { d["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 9; }),
              names("node 0", "light 9"));
  EXPECT_THAT(broken([](json& d) { d["nodes"][3]["scale"] = {0.0, 0.0, 0.0}; }), HasSubstr("no direction"));
}

}  // namespace
}  // namespace phyir::scenes
