// `scenes info` content: counts, materials, the emitted-power estimate (checked against
// pi * L * A computed here from the quad's geometry), cameras, viewpoints, warnings.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "gltf_test_helpers.h"
#include "phyir/core/safe_math.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/scene_info.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using test::GltfBuilder;
using ::testing::HasSubstr;

// A 2 m x 1.5 m emissive quad (radiance 5 * (1, 0.5, 0.25)), one-sided, plus a camera.
Scene load_lamp_scene() {
  GltfBuilder b;
  b.add_triangles("lamp", {{0, 0, 0}, {2, 0, 0}, {2, 1.5f, 0}, {0, 1.5f, 0}}, {0, 1, 2, 0, 2, 3}, {},
                  {{"material", 0}});
  b.doc["materials"] = {{{"name", "panel"},
                         {"emissiveFactor", {1, 0.5, 0.25}},
                         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 5}}}}}}};
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_materials_sheen"};
  b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
  const int lamp = b.add_node({{"mesh", 0}});
  const int eye = b.add_node({{"camera", 0}, {"translation", {1, 1, 4}}});
  b.set_scene({lamp, eye});
  b.doc["scenes"][0]["extras"] = {{"phyir", {{"candidate_viewpoints", {{1, 1, 3}}}}}};
  return load_gltf(b.write_gltf(test::fresh_test_dir(), "lamp"));
}

TEST(SceneInfo, JsonCountsMaterialsEmittersCamerasAndWarnings) {
  const Scene scene = load_lamp_scene();
  const json info = scene_info_json(scene);
  EXPECT_EQ(info["meshes"], 1);
  EXPECT_EQ(info["triangles"], 2);
  EXPECT_EQ(info["source_info"]["mesh_instances"], 1);
  EXPECT_EQ(info["source_info"]["cameras"], 1);
  EXPECT_EQ(info["source_info"]["generator"], "phyir loader tests");
  ASSERT_EQ(info["materials"].size(), 1u);
  EXPECT_EQ(info["materials"][0]["name"], "panel");
  EXPECT_EQ(info["materials"][0]["emissive"], true);
  EXPECT_EQ(info["materials"][0]["transmissive"], false);
  EXPECT_EQ(info["materials"][0]["extensions"], json({"KHR_materials_emissive_strength"}));

  const double area = 2.0 * 1.5;
  EXPECT_EQ(info["emitters"]["meshes"], 1);
  EXPECT_EQ(info["emitters"]["triangles"], 2);
  EXPECT_NEAR(info["emitters"]["area_m2"].get<double>(), area, 1e-6);
  const double radiance[3] = {5.0, 2.5, 1.25};
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(info["emitters"]["power_w"][c].get<double>(), kPi * radiance[c] * area, 1e-4);

  ASSERT_EQ(info["cameras"].size(), 1u);
  EXPECT_EQ(info["cameras"][0]["position"], json({1.0, 1.0, 4.0}));
  EXPECT_EQ(info["candidate_viewpoints"], json({{1.0, 1.0, 3.0}}));
  EXPECT_EQ(info["bounds"]["max"], json({2.0, 1.5, 0.0}));
  ASSERT_EQ(info["warnings"].size(), 1u);
  EXPECT_THAT(info["warnings"][0].get<std::string>(), HasSubstr("KHR_materials_sheen ignored"));
}

TEST(SceneInfo, TextNamesTheSameFacts) {
  const std::string text = scene_info_text(load_lamp_scene());
  EXPECT_THAT(text, HasSubstr("geometry: 1 meshes, 2 triangles"));
  EXPECT_THAT(text, HasSubstr("[0] panel: 1 meshes; KHR_materials_emissive_strength; emissive"));
  EXPECT_THAT(text, HasSubstr("emitters: 1 meshes, 2 triangles, 3 m^2"));
  EXPECT_THAT(text, HasSubstr("candidate viewpoints: 1"));
  EXPECT_THAT(text, HasSubstr("KHR_materials_sheen ignored"));
}

// The command itself: JSON on stdout for a Khronos file, an error and exit 1 for a bad one.
std::string run(const std::string& command, int* status) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe.get())) out.append(buffer, n);
  *status = pclose(pipe.release());
  return out;
}

TEST(SceneInfoCommand, JsonForAKhronosFileAndExitOneForABadFile) {
  const std::string binary = PHYIR_BINARY;
  const std::string khronos = std::string(PHYIR_SHARED_DIR) + "/testdata/khronos/SimpleMeshes.gltf";
  int status = 0;
  const json info = json::parse(run(binary + " scenes info --json '" + khronos + "' 2>/dev/null", &status));
  EXPECT_EQ(status, 0);
  EXPECT_EQ(info["source_info"]["mesh_instances"], 2);
  EXPECT_EQ(info["triangles"], 2);

  const std::string bad = std::string(PHYIR_TEST_DATA_DIR) + "/gltf/missing_bin.gltf";
  const std::string err = run(binary + " scenes info '" + bad + "' 2>&1 >/dev/null", &status);
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_THAT(err, HasSubstr("buffer 0 uri 'missing.bin' not found"));
}

}  // namespace
}  // namespace phyir::scenes
