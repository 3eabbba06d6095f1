// KHR_materials_specular: the model's dielectric F0 is fixed at 0.04 (docs/brdf.md). The
// extension's default values (what Blender writes on every material) load silently; any
// other value is ignored with a warning naming it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gltf_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/scenes/gltf_loader.h"

namespace phyir::scenes {
namespace {

using nlohmann::json;
using ::testing::AllOf;
using ::testing::Contains;
using ::testing::HasSubstr;

constexpr const char* kSpecular = "KHR_materials_specular";

// A triangle drawn with material 0 'm' carrying KHR_materials_specular = `specular`.
Scene load_with_specular(const json& specular) {
  test::GltfBuilder b;
  b.add_triangles("tri", test::unit_triangle(), {0, 1, 2}, {}, {{"material", 0}});
  b.doc["materials"] = {{{"name", "m"}, {"extensions", {{kSpecular, specular}}}}};
  b.doc["extensionsUsed"] = {kSpecular};
  b.set_scene({b.add_node({{"mesh", 0}})});
  return load_gltf(b.write_gltf(test::fresh_test_dir(), "specular"));
}

bool any_warning_has(const Scene& scene, const std::string& text) {
  for (const std::string& w : scene.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

TEST(GltfSpecular, DefaultValuesAreAcceptedSilently) {
  for (const json& specular : {json::object(), json{{"specularFactor", 1}, {"specularColorFactor", {1, 1, 1}}}}) {
    const Scene scene = load_with_specular(specular);
    EXPECT_FALSE(any_warning_has(scene, kSpecular)) << specular.dump();
    EXPECT_THAT(scene.materials[0].extensions, Contains(kSpecular));
  }
}

TEST(GltfSpecular, OtherValuesWarnNamingWhatIsIgnored) {
  const Scene scene = load_with_specular({{"specularFactor", 0.5},
                                          {"specularColorFactor", {1, 0.5, 1}},
                                          {"specularColorTexture", {{"index", 0}}}});
  EXPECT_TRUE(any_warning_has(scene,
                              "material 0 'm' KHR_materials_specular specularFactor 0.5, specularColorFactor "
                              "[1, 0.5, 1], specularColorTexture ignored: the dielectric F0 stays 0.04"));
  // The material itself is unchanged: a dielectric F0 of 0.04 is the BRDF's, not a field.
  EXPECT_EQ(scene.materials[0].metallic_factor, 1.0f);
}

TEST(GltfSpecular, ATextureAloneWarns) {
  const Scene scene = load_with_specular({{"specularTexture", {{"index", 0}}}});
  EXPECT_TRUE(any_warning_has(scene, "KHR_materials_specular specularTexture ignored"));
}

TEST(GltfSpecular, MalformedColorIsAnError) {
  // Refused by the schema check or by the loader, whichever sees it first.
  try {
    load_with_specular({{"specularColorFactor", {1, 1}}});
    FAIL() << "loaded";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("'m'"), HasSubstr("KHR_materials_specular"),
                                HasSubstr("specularColorFactor")));
  }
}

}  // namespace
}  // namespace phyir::scenes
