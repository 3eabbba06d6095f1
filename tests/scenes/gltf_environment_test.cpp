// The environment a scene declares in its extras.phyir.environment: resolved beside the
// glTF file, scale read, and every malformed entry or missing file refused naming the file,
// the scene and the problem.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/scene_info.h"

namespace phyir::scenes {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::GltfBuilder;
using ::testing::AllOf;
using ::testing::HasSubstr;

// A triangle in a scene whose extras are `extras`, written to `dir` with an empty "sky.exr"
// and "my sky.exr" beside it (the loader only checks the file exists).
fs::path scene_with_extras(const fs::path& dir, const json& extras) {
  GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2});
  b.set_scene({b.add_node({{"mesh", 0}})});
  if (!extras.is_null()) b.doc["scenes"][0]["extras"] = extras;
  test::write_bytes(dir / "sky.exr", "x", 1);
  test::write_bytes(dir / "my sky.exr", "x", 1);
  return b.write_gltf(dir, "room");
}

json environment(const json& entry) { return {{"phyir", {{"environment", entry}}}}; }

std::string load_error(const fs::path& path) {
  try {
    load_gltf(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GltfEnvironment, AbsentMeansNone) {
  const fs::path dir = test::fresh_test_dir();
  EXPECT_FALSE(load_gltf(scene_with_extras(dir, nullptr)).environment.has_value());
  EXPECT_FALSE(load_gltf(scene_with_extras(dir, {{"phyir", {{"preset", "mini"}}}})).environment.has_value());
}

TEST(GltfEnvironment, UriResolvesBesideTheFileAndScaleDefaultsToOne) {
  const fs::path dir = test::fresh_test_dir();
  const Scene scene = load_gltf(scene_with_extras(dir, environment({{"uri", "sky.exr"}})));
  ASSERT_TRUE(scene.environment.has_value());
  EXPECT_EQ(scene.environment->uri, "sky.exr");
  EXPECT_EQ(scene.environment->path, dir / "sky.exr");
  EXPECT_EQ(scene.environment->scale, 1.0f);
  const Scene scaled = load_gltf(scene_with_extras(dir, environment({{"uri", "my%20sky.exr"}, {"scale", 0.25}})));
  EXPECT_EQ(scaled.environment->path, dir / "my sky.exr");  // percent-decoded
  EXPECT_EQ(scaled.environment->scale, 0.25f);
}

TEST(GltfEnvironment, ScenesInfoPrintsIt) {
  const fs::path dir = test::fresh_test_dir();
  const Scene scene = load_gltf(scene_with_extras(dir, environment({{"uri", "sky.exr"}, {"scale", 0.25}})));
  EXPECT_THAT(scene_info_text(scene), HasSubstr("environment: " + (dir / "sky.exr").string() + " x 0.25"));
  EXPECT_EQ(scene_info_json(scene)["environment"],
            json({{"uri", "sky.exr"}, {"path", (dir / "sky.exr").string()}, {"scale", 0.25}}));
  const Scene plain = load_gltf(scene_with_extras(dir, nullptr));
  EXPECT_THAT(scene_info_text(plain), HasSubstr("environment: none declared"));
  EXPECT_TRUE(scene_info_json(plain)["environment"].is_null());
}

TEST(GltfEnvironment, MissingFileNamesTheGltfTheUriAndThePathLookedFor) {
  const fs::path dir = test::fresh_test_dir();
  EXPECT_THAT(load_error(scene_with_extras(dir, environment({{"uri", "clouds.exr"}}))),
              AllOf(HasSubstr("room.gltf: scene 0 extras.phyir.environment uri 'clouds.exr' not found"),
                    HasSubstr((dir / "clouds.exr").string())));
}

TEST(GltfEnvironment, MalformedEntriesAreRefused) {
  const fs::path dir = test::fresh_test_dir();
  const auto error = [&](const json& entry) { return load_error(scene_with_extras(dir, environment(entry))); };
  EXPECT_THAT(error("sky.exr"), HasSubstr("room.gltf: scene 0 extras.phyir.environment is not an object"));
  EXPECT_THAT(error({{"scale", 1.0}}), HasSubstr("extras.phyir.environment needs a 'uri'"));
  EXPECT_THAT(error({{"uri", 3}}), HasSubstr("needs a 'uri'"));
  EXPECT_THAT(error({{"uri", "data:image/x-exr;base64,AAAA"}}), HasSubstr("uri is a data: URI"));
  EXPECT_THAT(error({{"uri", "sky.exr"}, {"scale", -1.0}}), HasSubstr("environment scale is -1: must be >= 0"));
  EXPECT_THAT(error({{"uri", "sky.exr"}, {"scale", "bright"}}), HasSubstr("environment scale is not a finite number"));
  EXPECT_THAT(error({{"uri", "sky.exr"}, {"rotation", 90}}),
              HasSubstr("has an unknown member 'rotation': the members are uri and scale"));
}

}  // namespace
}  // namespace phyir::scenes
